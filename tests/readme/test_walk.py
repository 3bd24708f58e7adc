"""ctest readme.selftest: walk.py catches what it is there to catch — a command that fails or runs
past its budget fails the walk with the page, the line and the output's tail; a skip without a
reason, an unknown marker and an untagged fence are refused; what a reader types carries from
one command to the next, and a skipped block is not run."""
import os
import subprocess
import sys

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import walk  # noqa: E402

FIXTURES = os.path.join(HERE, "fixtures")


def run_walk(tmp_path, page, budget=10):
    """walk.py on one fixture page, from a small source tree with an empty build folder."""
    source, build = tmp_path / "source", tmp_path / "build"
    source.mkdir()
    build.mkdir()
    (source / "README.md").write_text("a source tree without git: copied whole\n")
    (source / "docs").mkdir()
    (source / "docs" / "build.md").write_text("copied: only the root's build* are build outputs\n")
    (source / "build-other").mkdir()
    return subprocess.run([sys.executable, os.path.join(HERE, "walk.py"), "--source", str(source),
                           "--build", str(build), "--budget", str(budget),
                           os.path.join(FIXTURES, page)], capture_output=True, text=True,
                          timeout=60)


def test_a_page_that_runs_passes_and_its_skipped_block_is_not_run(tmp_path):
    result = run_walk(tmp_path, "passes.md")
    assert result.returncode == 0, result.stdout + result.stderr
    assert "skip " in result.stdout and "it would fail" in result.stdout
    # Four commands in the sh block's six lines (one a comment, two joined by a continuation), three
    # in the console block; the ```text synopsis is not run.
    assert result.stdout.count("run  ") == 7, result.stdout


def test_a_failing_command_fails_the_walk_with_page_line_and_output(tmp_path):
    result = run_walk(tmp_path, "fails.md")
    assert result.returncode == 1
    assert "fails.md:5: exited 3" in result.stderr, result.stderr
    assert "the tail the report shows" in result.stderr
    assert "never run" not in result.stdout  # the page stops at its first failure


def test_a_command_past_its_budget_fails_the_walk(tmp_path):
    result = run_walk(tmp_path, "slow.md", budget=1)
    assert result.returncode == 1
    assert "slow.md:4: ran past its budget of 1 s" in result.stderr, result.stderr


@pytest.mark.parametrize("page, message", [
    ("skip-no-reason.md", "needs its reason"),
    ("untagged.md", "a fence without a language"),
])
def test_a_refused_page_fails_the_walk(tmp_path, page, message):
    result = run_walk(tmp_path, page)
    assert result.returncode == 1
    assert message in result.stderr, result.stderr


def page_of(tmp_path, text):
    path = tmp_path / "page.md"
    path.write_text(text)
    return str(path)


def test_markers_are_read_with_their_reason_and_refused_otherwise(tmp_path):
    blocks = walk.read_page(page_of(tmp_path, "<!-- readme-walk: skip (slow: 4 min) -->\n\n"
                                              "```sh\nfalse\n```\n"))
    assert blocks[0].skip_reason == "slow: 4 min"
    # A marker quoted in prose is text, not a marker.
    quoted = walk.read_page(page_of(tmp_path, "Write `<!-- readme-walk: skip (why) -->`.\n\n"
                                              "```sh\ntrue\n```\n"))
    assert quoted[0].skip_reason is None
    for bad in ("<!-- readme-walk: skip -->\n```sh\nx\n```\n",          # no reason
                "<!-- readme-walk: skipp (typo) -->\n```sh\nx\n```\n",  # unknown marker
                "<!-- readme-walk: skip (why) -->\ntext\n```sh\nx\n```\n",  # not right before
                "<!-- readme-walk: skip (why) -->\n```ini\nx = 1\n```\n",   # not a shell block
                "<!-- readme-walk skip (why) -->\n```sh\nx\n```\n",   # no colon: a typo
                "<!-- readme-walk: skip (why) -->\n"):                     # no block after it
        with pytest.raises(walk.PageError):
            walk.read_page(page_of(tmp_path, bad))


def test_continuations_and_comments_make_one_command_per_logical_line():
    body = ["# comment", "a --x \\", "  --y   # trailing", "", "b"]
    commands = walk.shell_commands(body, 10)
    assert [(c.line, c.text) for c in commands] == [(11, "a --x \\\n  --y   # trailing"),
                                                     (14, "b")]


def test_console_blocks_run_the_prompt_lines_only():
    body = ["$ a \\", "  --y", "output", "$ b"]
    assert [c.text for c in walk.console_commands(body, 1)] == ["a \\\n  --y", "b"]
