"""Writing a results page of docs/results/: the page (atomically), Markdown table lines and
cells, a section one study keeps in another study's page, and the sentence on the machine a
study ran on, which every page records: on a shared machine the load is what makes two wall
times comparable or not, and the commit says which code made the numbers."""
import json
import os
import platform
import re
import statistics
import subprocess
import time

from .apps import ROOT

RESULTS = os.path.join(ROOT, "docs", "results")


def write_page(name, text):
    """Writes docs/results/`name` through a temporary file renamed over it (an interrupted study
    leaves the old page, never half a new one); returns the path."""
    os.makedirs(RESULTS, exist_ok=True)
    path = os.path.join(RESULTS, name)
    with open(path + ".tmp", "w") as f:
        f.write(text)
    os.replace(path + ".tmp", path)
    return path


TEMPLATES = os.path.join(ROOT, "bench", "studies", "templates")


def fill_template(name, values):
    """bench/studies/templates/`name` with each {{key}} replaced by str(values[key]): a study's
    prose lives in its template, the study fills in what it measured. A key without a value is
    a KeyError naming the template."""
    path = os.path.join(TEMPLATES, name)
    with open(path) as f:
        template = f.read()

    def sub(m):
        if m.group(1) not in values:
            raise KeyError(f"{path}: no value for {{{{{m.group(1)}}}}}")
        return str(values[m.group(1)])
    return re.sub(r"\{\{(\w+)\}\}", sub, template)


def read_page(name):
    """The text of docs/results/`name`, or "" when there is none."""
    path = os.path.join(RESULTS, name)
    if not os.path.exists(path):
        return ""
    with open(path) as f:
        return f.read()


DISCUSSION = "<!-- discussion: kept when the script rewrites this page -->"


def write_page_with_discussion(name, text):
    """write_page of `text` followed by the page's hand-written discussion as it stands: from the
    DISCUSSION marker on (the marker alone when the page has none), so a study that regenerates
    its page keeps what people wrote under it."""
    old = read_page(name)
    tail = old[old.index(DISCUSSION):] if DISCUSSION in old else DISCUSSION + "\n"
    return write_page(name, text.rstrip("\n") + "\n\n" + tail)


def section_markers(key):
    """The HTML comments around a section of a page that another study writes."""
    return f"<!-- {key}:begin -->", f"<!-- {key}:end -->"


def marked_section(text, key):
    """The section `key` of a page's text, markers included, or None when it has none."""
    begin, end = section_markers(key)
    if begin not in text:
        return None
    return text[text.index(begin):text.index(end) + len(end)]


def splice(text, key, block):
    """`text` with `block` (markers included) in place of its section `key`, or after its end
    when it has none."""
    begin, end = section_markers(key)
    if begin in text:
        return text[:text.index(begin)] + block + text[text.index(end) + len(end):]
    return text.rstrip("\n") + "\n\n" + block + "\n"


def write_page_keeping(name, text, keys):
    """write_page with the sections `keys` that other studies keep in this page carried over
    from the page as it is (each study regenerates only its own part)."""
    old = read_page(name)
    for key in keys:
        kept = marked_section(old, key)
        if kept:
            text = splice(text, key, kept)
    return write_page(name, text)


def table_row(*cells):
    """One line of a Markdown table."""
    return "| " + " | ".join(str(c) for c in cells) + " |"


def table_head(*columns):
    """The header line and the rule line of a Markdown table, with as many rule cells as
    columns."""
    return [table_row(*columns), "|" + "---|" * len(columns)]


def summary(values):
    """mean, min, max, sd (sample; 0 for one value) of a list of numbers."""
    sd = statistics.stdev(values) if len(values) > 1 else 0.0
    return statistics.mean(values), min(values), max(values), sd


def load_average():
    """The 1, 5 and 15 min load averages now, as text ("1.44 1.30 1.23"): what machine() takes,
    and what a study stores with its measurements."""
    return " ".join(f"{x:.2f}" for x in os.getloadavg())


def _git(*args):
    proc = subprocess.run(["git", "-C", ROOT, *args], capture_output=True, text=True)
    return proc.stdout.strip() if proc.returncode == 0 else None


def _host():
    """The CPU model, and whether the CPU flags name a hypervisor (a virtual machine)."""
    model, virtual = None, False
    if os.path.exists("/proc/cpuinfo"):
        for line in open("/proc/cpuinfo"):
            key, _, value = line.partition(":")
            if key.strip() == "model name" and model is None:
                model = value.strip()
            elif key.strip() == "flags" and "hypervisor" in value.split():
                virtual = True
    model = model or platform.processor() or platform.machine() or "unknown CPU"
    return model + (", virtual machine" if virtual else "")


def source(program=None):
    """Where the numbers' code came from: the commit checked out, marked when files outside
    docs/results differ from it; with `program` (a program of the build), also when that was
    built and the last commit before."""
    commit = _git("rev-parse", "--short", "HEAD")
    if commit is None:
        text = "commit unknown (no git checkout)"
    else:
        changed = _git("status", "--porcelain", "--untracked-files=no", "--", ".",
                       ":!docs/results")
        text = f"commit {commit}" + (" with uncommitted changes" if changed else "")
    if program:
        built = time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime(os.path.getmtime(program)))
        before = _git("log", "-1", "--format=%h", f"--before={built}")
        text += f"; {os.path.basename(program)} built {built}, after commit {before or '?'}"
    return text


def machine(load_before, load_after=None, program=None, source_text=None):
    """The sentence a page gives on where its numbers were measured: the host (CPU model, and
    whether virtual), its cores, the platform, the load average (1, 5, 15 min) before the runs
    (`load_before`, from load_average()) and after them (`load_after`, default now), and the
    source (source(program), or `source_text`: what source() said when the numbers were taken)."""
    load_after = load_after or load_average()
    return (f"Machine: {_host()}, {os.cpu_count()} cores, {platform.platform()}; load average "
            f"(1, 5, 15 min) {load_before} before the runs, {load_after} after; source at "
            f"{source_text or source(program)}.")


def record_batches(path, ran, load_before, program):
    """The calls of a study that ran rows, kept in `path` (its results.json: {"batches": [{"keys",
    "machine"}]}): the stored ones and this call's, when it ran rows (`ran`, their keys), with
    machine(load_before, program=program); a row belongs to the last call that ran it, and a
    call left with none is dropped. Writes them back and returns them."""
    stored = json.load(open(path))["batches"] if os.path.exists(path) else []
    batches = stored + ([{"keys": ran, "machine": machine(load_before, program=program)}] if ran else [])
    batches = [dict(b, keys=[k for k in b["keys"] if not any(k in later["keys"] for later in batches[i + 1:])])
               for i, b in enumerate(batches)]
    batches = [b for b in batches if b["keys"]]
    with open(path, "w") as f:
        json.dump({"batches": batches}, f, indent=1)
    return batches


def batch_lines(batches):
    """The Machine sentence of each call that ran rows of a page (record_batches), naming its rows
    when there are several, with Markdown line breaks between them."""
    lines = [(f"Rows {', '.join(b['keys'])}: " if len(batches) > 1 else "") + b["machine"] for b in batches]
    return [line + "  " if i < len(lines) - 1 else line for i, line in enumerate(lines)]
