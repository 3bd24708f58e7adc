"""lib/report.py: the page helpers and the machine sentence. Run from bench/studies:
python3 -m pytest lib/tests"""
import os

import pytest

from lib import report


def test_table_lines():
    assert report.table_head("a", "b c") == ["| a | b c |", "|---|---|"]
    assert report.table_row(1, 2.5, "x") == "| 1 | 2.5 | x |"


def test_summary():
    assert report.summary([1.0, 2.0, 3.0]) == (2.0, 1.0, 3.0, pytest.approx(1.0))
    assert report.summary([4.0]) == (4.0, 4.0, 4.0, 0.0)


def test_sections():
    begin, end = report.section_markers("part")
    block = f"{begin}\nnew\n{end}"
    page = f"head\n\n{begin}\nold\n{end}\ntail\n"
    assert report.marked_section(page, "part") == f"{begin}\nold\n{end}"
    assert report.marked_section("head\n", "part") is None
    assert report.splice(page, "part", block) == f"head\n\n{block}\ntail\n"
    assert report.splice("head\n\n", "part", block) == f"head\n\n{block}\n"


def test_write_page_replaces_whole(tmp_path, monkeypatch):
    monkeypatch.setattr(report, "RESULTS", str(tmp_path))
    assert report.read_page("p.md") == ""
    path = report.write_page("p.md", "one\n")
    report.write_page("p.md", "two\n")
    assert path == os.path.join(str(tmp_path), "p.md")
    assert report.read_page("p.md") == "two\n"
    assert os.listdir(tmp_path) == ["p.md"]


def test_write_page_with_discussion_keeps_what_people_wrote(tmp_path, monkeypatch):
    monkeypatch.setattr(report, "RESULTS", str(tmp_path))
    marker = report.DISCUSSION
    report.write_page_with_discussion("p.md", "table one\n")
    assert report.read_page("p.md") == f"table one\n\n{marker}\n"
    with open(os.path.join(str(tmp_path), "p.md"), "a") as f:
        f.write("\nWhy the numbers moved.\n")
    report.write_page_with_discussion("p.md", "table two")
    assert report.read_page("p.md") == f"table two\n\n{marker}\n\nWhy the numbers moved.\n"


def test_write_page_keeping_carries_other_studies_sections(tmp_path, monkeypatch):
    monkeypatch.setattr(report, "RESULTS", str(tmp_path))
    begin, end = report.section_markers("theirs")
    report.write_page("p.md", f"old body\n\n{begin}\nkept\n{end}\n")
    report.write_page_keeping("p.md", "new body\n", ["theirs", "absent"])
    assert report.read_page("p.md") == f"new body\n\n{begin}\nkept\n{end}\n"


def test_machine_names_cores_loads_and_source():
    text = report.machine("9.00 8.00 7.00", "1.00 2.00 3.00")
    assert text.startswith("Machine: ") and text.endswith(".")
    assert f"{os.cpu_count()} cores" in text
    assert "9.00 8.00 7.00 before the runs, 1.00 2.00 3.00 after" in text
    assert "source at commit " in text
    assert len(report.load_average().split()) == 3


def test_record_batches_keeps_each_row_under_the_last_call_that_ran_it(tmp_path):
    path = str(tmp_path / "results.json")
    first = report.record_batches(path, ["a", "b"], "1.00 1.00 1.00", None)
    assert [b["keys"] for b in first] == [["a", "b"]]
    assert report.record_batches(path, [], "1.00 1.00 1.00", None) == first  # ran nothing: no call
    later = report.record_batches(path, ["b"], "2.00 2.00 2.00", None)
    assert [b["keys"] for b in later] == [["a"], ["b"]]
    assert "2.00 2.00 2.00 before the runs" in later[1]["machine"]
    # Rerunning every row leaves one call; the file holds what was returned.
    again = report.record_batches(path, ["a", "b"], "3.00 3.00 3.00", None)
    assert [b["keys"] for b in again] == [["a", "b"]]
    assert report.record_batches(path, [], "0 0 0", None) == again


def test_batch_lines_name_the_rows_only_when_calls_differ():
    one = [{"keys": ["a"], "machine": "Machine: x."}]
    assert report.batch_lines(one) == ["Machine: x."]
    two = one + [{"keys": ["b", "c"], "machine": "Machine: y."}]
    assert report.batch_lines(two) == ["Rows a: Machine: x.  ", "Rows b, c: Machine: y."]


def test_fill_template(tmp_path, monkeypatch):
    monkeypatch.setattr(report, "TEMPLATES", str(tmp_path))
    (tmp_path / "page.md.in").write_text("# {{title}}\n\n{{table}} and {{title}} again; {single} kept\n")
    assert report.fill_template("page.md.in", {"title": "T", "table": 1.5}) == \
        "# T\n\n1.5 and T again; {single} kept\n"
    with pytest.raises(KeyError, match="page.md.in: no value for {{table}}"):
        report.fill_template("page.md.in", {"title": "T"})
