#!/usr/bin/env python3
"""ctest readme.walk.<doc>: every shell command a Markdown page shows runs as printed (issue 34).

usage: walk.py [--build DIR] [--source DIR] [--budget S] [--keep] PAGE.md...

What a reader would type: the ```sh, ```bash and ```shell blocks of each page (a line ending in a
backslash continues on the next; comment-only lines are not commands) and the `$ ` lines of
```console blocks, in the page's order, each in `bash` from the root of a scratch copy of the
repository's files (what a fresh clone holds: git's tracked and unignored files) with `build`
linked to the build folder, as a user who built it has. Variables and `cd` carry from one
command to the next, as in the reader's shell. A command that exits non-zero or runs past the
per-command budget fails the walk with the page, the line, and the tail of its output.

A block is skipped only by a marker the page carries on the last non-blank line before it, its
reason visible in the Markdown source:
    <!-- readme-walk: skip (takes ~2 min here: the main job) -->
A skip without a reason, an unknown readme-walk marker, a marker that is not before a shell
block, and a fence without a language (so that no command block escapes the walk untagged:
`text` for a synopsis or output) are refused."""
import argparse
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field

SHELL_LANGUAGES = {"sh", "bash", "shell"}
CONSOLE_LANGUAGE = "console"
# A marker is an HTML comment on a line of its own (one quoted in prose, in backticks, is text).
MARKER = re.compile(r"^\s*<!--\s*readme-walk:(.*?)-->\s*$")
SKIP = re.compile(r"^\s*skip\s*\((.*)\)\s*$")
FENCE = re.compile(r"^( {0,3})(`{3,}|~{3,})\s*([^`\s]*)")
OUTPUT_TAIL_LINES = 40


class PageError(Exception):
    """A page the walk cannot read as the rules above ask (a refused marker or fence)."""


@dataclass
class Command:
    line: int  # 1-based line of the page where the command starts
    text: str


@dataclass
class Block:
    line: int  # the opening fence's line
    language: str
    skip_reason: str | None = None
    commands: list[Command] = field(default_factory=list)


def marker_reason(line, where):
    """The skip reason of a marker line; None for any other line. Refuses a comment that names
    readme-walk but is not a marker the walk reads (a typo would otherwise drop the skip)."""
    stripped = line.strip()
    if not (stripped.startswith("<!--") and "readme-walk" in stripped):
        return None
    marker = MARKER.match(line)
    if not marker:
        raise PageError(f"{where}: not a readme-walk marker: '{stripped}' "
                        "(accepted: <!-- readme-walk: skip (REASON) --> on a line of its own)")
    return parse_marker(marker.group(1), where)


def parse_marker(text, where):
    """The skip reason a readme-walk marker gives; refuses any other marker and an empty reason."""
    match = SKIP.match(text)
    if not match:
        raise PageError(f"{where}: unknown readme-walk marker '{text.strip()}' "
                        "(accepted: <!-- readme-walk: skip (REASON) -->)")
    reason = match.group(1).strip()
    if not reason:
        raise PageError(f"{where}: a readme-walk skip needs its reason in the parentheses, "
                        "for the reader of the page")
    return reason


def shell_commands(body, first_line):
    """Commands of a sh block: joined over backslash continuations, comment-only lines left out."""
    commands, pending = [], None
    for number, line in enumerate(body, first_line):
        if pending is None:
            if not line.strip() or line.lstrip().startswith("#"):
                continue
            pending = Command(number, line)
        else:
            pending.text += "\n" + line
        if not line.endswith("\\"):
            commands.append(pending)
            pending = None
    if pending is not None:
        commands.append(pending)
    return commands


def console_commands(body, first_line):
    """Commands of a console block: the `$ ` lines and their continuations; the rest is output."""
    commands, continuing = [], False
    for number, line in enumerate(body, first_line):
        if continuing:
            commands[-1].text += "\n" + line
        elif line.startswith("$ "):
            commands.append(Command(number, line[2:]))
        else:
            continue
        continuing = line.endswith("\\")
    return commands


def commands_of(language, body, first_line):
    if language == CONSOLE_LANGUAGE:
        return console_commands(body, first_line)
    return shell_commands(body, first_line)


def closing_fence(lines, start, fence):
    """Index of the line that closes a block opened with `fence` at `start` (CommonMark's rule)."""
    for index in range(start + 1, len(lines)):
        stripped = lines[index].strip()
        if stripped and set(stripped) == {fence[0]} and len(stripped) >= len(fence):
            return index
    return len(lines)


def fenced_block(lines, index, fence, where, marked):
    """(Block or None, index of the closing fence) for the fence opened at `index`; `marked`: the
    marker's place when a skip marker stands before it, else None."""
    indent, ticks, language = fence.groups()
    end = closing_fence(lines, index, ticks)
    if not language:
        raise PageError(f"{where}: a fence without a language: write ```sh for commands the walk "
                        "runs, ```text for a synopsis or output")
    if language not in SHELL_LANGUAGES and language != CONSOLE_LANGUAGE:
        if marked:
            raise PageError(f"{marked[0]}: a readme-walk marker before a ```{language} block "
                            "(only shell blocks are walked)")
        return None, end
    # Content indented like its fence (in a list item) is read without that indentation.
    body = [line[len(indent):] if line.startswith(indent) else line
            for line in lines[index + 1:end]]
    reason = marked[1] if marked else None
    return Block(index + 1, language, reason, commands_of(language, body, index + 2)), end


def read_page(path, name=None):
    """The page's shell blocks, with their skip markers; raises PageError on a refused page."""
    lines = open(path, encoding="utf-8").read().splitlines()
    path = name or path
    blocks, marked, index = [], None, 0  # marked: (where, reason) of a pending skip marker
    while index < len(lines):
        line, where = lines[index], f"{path}:{index + 1}"
        fence = FENCE.match(line)
        if fence:
            block, index = fenced_block(lines, index, fence, where, marked)
            blocks += [block] if block else []
            marked = None
        elif (reason := marker_reason(line, where)) is not None:
            marked = (where, reason)
        elif line.strip() and marked:
            raise PageError(f"{marked[0]}: a readme-walk marker must be the last non-blank line "
                            "before a shell block")
        index += 1
    if marked:
        raise PageError(f"{marked[0]}: a readme-walk marker with no block after it")
    return blocks


def tracked_files(source):
    """What a fresh clone of `source` holds: git's tracked and unignored files (None: no git)."""
    try:
        listed = subprocess.run(["git", "-C", source, "ls-files", "-z", "--cached", "--others",
                                 "--exclude-standard"], capture_output=True, check=True)
    except (OSError, subprocess.CalledProcessError):
        return None
    return [name for name in listed.stdout.decode().split("\0")
            if name and os.path.isfile(os.path.join(source, name))]


def build_outputs(source):
    """copytree's ignore: the root's build folders, out/ and .git (docs/build.md is a page)."""
    root = os.path.abspath(source)

    def ignored(folder, names):
        if os.path.abspath(folder) != root:
            return []
        return [name for name in names if name.startswith("build") or name in ("out", ".git")]
    return ignored


def make_checkout(source, build, scratch):
    """A copy of the repository's files in `scratch` with `build` linked to the build folder."""
    names = tracked_files(source)
    if names is None:  # a source tree without git (an unpacked archive): all but build outputs
        shutil.copytree(source, scratch, dirs_exist_ok=True, symlinks=True,
                        ignore=build_outputs(source))
    else:
        for name in names:
            os.makedirs(os.path.join(scratch, os.path.dirname(name)), exist_ok=True)
            shutil.copy2(os.path.join(source, name), os.path.join(scratch, name))
    link = os.path.join(scratch, "build")
    if os.path.lexists(link):
        raise PageError(f"{link}: the source tree has a tracked 'build' entry; the walk links "
                        "the build folder there")
    os.symlink(os.path.abspath(build), link)


# The command runs in bash with `set -a` (assignments are exported, so a plain VAR=... carries to
# the next command as in the reader's shell); after it, the environment and the folder are saved
# for the next command. The command's own status is the script's.
RUNNER = """set -a -o pipefail
cd "$WALK_CWD" || exit 97
{command}
walk_status=$?
env -0 > "$WALK_STATE/env"; pwd > "$WALK_STATE/cwd"
exit $walk_status
"""


@dataclass
class Session:
    """The reader's shell between commands: its environment and current folder."""
    env: dict
    cwd: str
    state: str  # folder the runner saves them in

    def load(self):
        """Takes up what the command left; a command that ended the shell itself (`exit 0`)
        left nothing, and the session stays as it was."""
        if not os.path.exists(os.path.join(self.state, "cwd")):
            return
        with open(os.path.join(self.state, "env"), "rb") as saved:
            pairs = [item.split(b"=", 1) for item in saved.read().split(b"\0") if b"=" in item]
        self.env = {key.decode(): value.decode(errors="surrogateescape") for key, value in pairs}
        with open(os.path.join(self.state, "cwd"), encoding="utf-8") as saved:
            self.cwd = saved.read().strip()


def run_command(command, session, budget):
    """(status, output) of one command; status None when it ran past the budget (then killed)."""
    env = dict(session.env, WALK_CWD=session.cwd, WALK_STATE=session.state)
    for saved in ("env", "cwd"):  # what the previous command left is not this one's
        if os.path.exists(os.path.join(session.state, saved)):
            os.remove(os.path.join(session.state, saved))
    process = subprocess.Popen(["bash", "-c", RUNNER.format(command=command.text)], env=env,
                               cwd=session.cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                               stdin=subprocess.DEVNULL, start_new_session=True)
    try:
        output, _ = process.communicate(timeout=budget)
        status = process.returncode
    except subprocess.TimeoutExpired:
        os.killpg(process.pid, signal.SIGKILL)  # the whole group: mpirun's ranks too
        output, _ = process.communicate()
        status = None
    if status == 0:
        session.load()
    return status, output.decode(errors="replace")


def failure_report(page, command, status, output, budget):
    what = f"ran past its budget of {budget:g} s" if status is None else f"exited {status}"
    tail = "\n".join(output.splitlines()[-OUTPUT_TAIL_LINES:])
    return f"FAIL {page}:{command.line}: {what}\n$ {command.text}\n{tail}"


def walk_page(page, blocks, session, budget):
    """Runs the page's unskipped commands in order; returns the failure reports (stops at one)."""
    for block in blocks:
        if block.skip_reason is not None:
            print(f"skip {page}:{block.line} ({block.skip_reason})", flush=True)
            continue
        for command in block.commands:
            print(f"run  {page}:{command.line}: {command.text.splitlines()[0]}", flush=True)
            start = time.monotonic()
            status, output = run_command(command, session, budget)
            print(f"     {time.monotonic() - start:.1f} s", flush=True)  # how near the budget
            if status != 0:
                # The commands after it read what it would have written: stop the page here.
                return [failure_report(page, command, status, output, budget)]
    return []


def shown(page, source):
    """The page as a reader names it: relative to the repository root when it lies in it."""
    relative = os.path.relpath(os.path.abspath(page), os.path.abspath(source))
    return page if relative.startswith("..") else relative


def walk(pages, source, build, budget, keep):
    """Walks each page in a scratch checkout of its own; returns the failure reports."""
    failures = []
    for path in pages:
        page = shown(path, source)
        try:
            blocks = read_page(path, page)
        except PageError as error:
            failures.append(f"FAIL {error}")
            continue
        scratch = tempfile.mkdtemp(prefix="readme-walk-")
        try:
            checkout, state = os.path.join(scratch, "repo"), os.path.join(scratch, "state")
            os.makedirs(state)
            make_checkout(source, build, checkout)
            failures += walk_page(page, blocks, Session(dict(os.environ), checkout, state), budget)
        finally:
            if keep:
                print(f"scratch folder kept: {scratch}")
            else:
                shutil.rmtree(scratch, ignore_errors=True)
    return failures


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("pages", nargs="+", help="Markdown pages, walked in the order given")
    parser.add_argument("--source", default=".", help="repository root (default: .)")
    parser.add_argument("--build", default="build", help="build folder linked as build/")
    parser.add_argument("--budget", type=float, default=60, help="seconds per command")
    parser.add_argument("--keep", action="store_true", help="keep the scratch folders")
    args = parser.parse_args()
    failures = walk(args.pages, args.source, args.build, args.budget, args.keep)
    for report in failures:
        print(report, file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
