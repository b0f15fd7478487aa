"""Which line of a YAML text is indented wrongly, found by trying.

PyYAML reports where its parser got stuck, and for an indentation mistake that is often not the
mistaken line: a first key indented too far is only wrong once the key after it arrives, and a
list item indented one space short is only wrong when the next item (maybe twenty lines on)
lines up differently. :func:`find_fix` re-indents each line near the problem (alone, or with
the lines under it) to an indentation used nearby and keeps the changes after which the text
parses. Several may (line 7 too deep, or line 8 too shallow); the one that also mends the lines
after the problem and leaves the file most like the rest of it wins: no key left with nothing
under it, nesting steps like the file's usual step, the moved line lined up with its
neighbours, the smallest move, the earliest line.

Measured on every single-line and single-block shift by 1 or 2 spaces of the repository's tree
files, examples and HTN domain that makes them invalid YAML, the line named is the shifted one
in 96-99% of cases (PyYAML's own mark: 66-71%); the rest are truly ambiguous (a key between two
blocks that could belong to either).
"""

from __future__ import annotations

import re
from collections import Counter
from dataclasses import dataclass

import yaml

_FAST_LOADER = getattr(yaml, "CSafeLoader", yaml.SafeLoader)  # only to try fixes: libyaml is ~20x faster
# Characters parsed while trying fixes, at most: about a second, with libyaml or without it.
MAX_TRIED_TEXT = 2_000_000 if _FAST_LOADER is not yaml.SafeLoader else 100_000
MAX_FULL_TRIES = 8  # best fixes checked against the lines after the problem too
MAX_PART_BLOCKS = 3  # a line moved with its first 1, 2 or 3 children, besides alone and with all
NEARBY_LINES = 3  # content lines before the problem that may be the mistaken one
MAX_SPAN = 400  # suspects at most this many lines above the problem
REACH_LINES = 200  # lines after the problem that tell apart fixes that all mend the problem
MARGIN_LINES = 2  # content lines after the problem a fix must also get past
_DASHES = re.compile(r"(?:-[ ]+)+")


@dataclass(frozen=True)
class Fix:
    """Move ``count`` lines starting at ``line`` (0-based) from indentation ``old`` to ``new``."""

    line: int
    count: int
    old: int
    new: int

    def applied_to(self, lines: list[str], i: int) -> str:
        """Line ``i`` of ``lines`` after this move (blank and comment lines under it stay)."""
        line = lines[i]
        if not (self.line <= i < self.line + self.count and (i == self.line or is_content(line))):
            return line
        shift = self.new - self.old
        return " " * shift + line if shift >= 0 else line[min(-shift, indent_of(line)):]

    def apply(self, lines: list[str]) -> list[str]:
        return [self.applied_to(lines, i) for i in range(len(lines))]


def find_fix(lines: list[str], problem: int, context: int | None = None) -> Fix | None:
    """The re-indentation of one line (or one line and the lines under it) near line ``problem``
    (0-based) after which ``lines`` parse, the most plausible one when several do; ``None`` when
    none does (or trying would take too long on a huge file)."""
    content = [i for i, line in enumerate(lines) if is_content(line)]
    if not content:
        return None
    return _Search(lines, content, min(problem, content[-1]), context).best()


@dataclass(frozen=True)
class _Style:
    """How the rest of the file is indented: the usual nesting step, and whether a key's list
    may start at the key's own indentation (``children:`` then ``- a`` right below it)."""

    step: int
    indentless: bool


class _Search:
    """Tries re-indenting lines near a problem; see the module docstring.

    A try parses only the lines from the first suspect to a little past the problem, after the
    lines they sit under (``root:``, ``sequence:``, ...) as a header, so a mistake deep in a
    large file costs what it costs in a small one."""

    def __init__(self, lines: list[str], content: list[int], problem: int, context: int | None) -> None:
        self.lines, self.content, self.problem = lines, content, problem
        self.before = [i for i in content if i < problem][-NEARBY_LINES:]
        after = [i for i in content if i > problem][:MARGIN_LINES]
        self.end = (after[-1] + 1) if after else len(lines)
        nearby = {*self.before, problem, *_context_lines(content, context), *self._enclosing()}
        self.candidates = sorted(i for i in nearby & set(content) if i >= problem - MAX_SPAN)
        self.style = _style(lines, content, set(self.candidates))
        window = [i for i in content if self.candidates[0] - 10 <= i < self.end]
        self.indents = sorted({indent_of(lines[i]) for i in window} | {content_column(lines[i]) for i in window}
                              | {content_column(lines[i]) + self.style.step for i in window if opens_block(lines[i])})
        self.view = self._view(self.end)
        if _parses_past(self._text(self.view, None), len(self.view)):  # the cut hides the problem
            self.view = list(range(self.end))

    def _enclosing(self) -> list[int]:
        """The lines the problem line sits under, and the first line of each of their blocks,
        when they start near its indentation: a block's first entry indented unlike the rest, or
        a key indented wrongly with its block, shows only at a later line."""
        near = indent_of(self.lines[self.problem])
        found, floor, below = [], near, self.problem
        for i in reversed([i for i in self.content if i < self.problem]):
            if indent_of(self.lines[i]) < floor:
                floor = indent_of(self.lines[i])
                found += [n for n in (i, below) if abs(indent_of(self.lines[n]) - near) <= 4]
            below = i
        return found

    def _view(self, end: int) -> list[int]:
        """The lines a try parses: the lines the first suspect sits under (each less indented
        than the one after it), then everything from the first suspect up to ``end``. The lines
        skipped are earlier entries of those blocks: they do not change how the rest is read."""
        first = self.candidates[0]
        floor = indent_of(self.lines[first])
        header: list[int] = []
        for i in reversed([i for i in self.content if i < first]):
            if floor == 0:
                break
            if indent_of(self.lines[i]) < floor:
                header.insert(0, i)
                floor = indent_of(self.lines[i])
        return [*header, *range(first, end)]

    def _text(self, view: list[int], fix: Fix | None) -> list[str]:
        if fix is None:
            return [self.lines[i] for i in view]
        return [fix.applied_to(self.lines, i) for i in view]

    def best(self) -> Fix | None:
        size = sum(len(self.lines[i]) + 1 for i in self.view)
        tries = [fix for line in self.candidates for fix in _fixes_of(self.lines, line, self.indents)]
        if not tries or len(tries) * size > MAX_TRIED_TEXT:
            return None
        top = self.view[0] == self.content[0]
        as_is = _oddness(self._text(self.view, None), self.style, top)
        scored = [(_oddness(moved, self.style, top), fix) for fix in tries
                  if _parses_past(moved := self._text(self.view, fix), len(self.view))]
        plausible = sorted(((odd, fix) for odd, fix in scored if odd <= as_is),  # no less tidy than before
                           key=lambda s: self._rank(*s))[:MAX_FULL_TRIES]
        if len(plausible) < 2:
            return plausible[0][1] if plausible else None
        # Several fixes mend these lines; the right one also mends the lines after them.
        longer = self._view(min(len(self.lines), self.end + REACH_LINES))
        return min(plausible, key=lambda s: (-_reach(self._text(longer, s[1])), self._rank(*s)))[1]

    def _rank(self, odd: int, fix: Fix) -> tuple[int, ...]:
        """Smaller is likelier: tidy, few lines moved, the moved line lined up with the lines
        on both sides, a small move, close to where the parser stopped, in the block above it."""
        previous = indent_of(self.lines[self.before[-1]]) if self.before else 0
        return (odd, fix.count, not self._lined_up(fix), abs(fix.new - fix.old), self.problem - fix.line,
                fix.new != previous, -fix.new)

    def _lined_up(self, fix: Fix) -> bool:
        above = [i for i in self.content if i < fix.line][-1:]
        below = [i for i in self.content if i >= fix.line + fix.count][:1]
        return bool(above and below) and indent_of(self.lines[above[0]]) == fix.new == indent_of(self.lines[below[0]])


def _context_lines(content: list[int], context: int | None) -> list[int]:
    """The line where the collection PyYAML was reading began, and the line after it: the first
    entry of a block decides its indentation, so it may be the odd one out."""
    if context is None:
        return []
    following = [i for i in content if i > context][:1]
    return [context, *following]


def _fixes_of(lines: list[str], line: int, indents: list[int]) -> list[Fix]:
    """Moves of ``line`` alone, and with the lines under it: all of them, or its first few
    children (the rest may be siblings that belong where they are)."""
    return [Fix(line, count, indent_of(lines[line]), new) for new in indents if new != indent_of(lines[line])
            for count in _block_sizes(lines, line)]


def _block_sizes(lines: list[str], line: int) -> list[int]:
    old = indent_of(lines[line])
    sizes, children = [1], None
    for i in range(line + 1, len(lines)):
        if not is_content(lines[i]):
            continue
        indent = indent_of(lines[i])
        if indent <= old:
            break
        if children is not None and indent <= children and len(sizes) <= MAX_PART_BLOCKS:
            sizes.append(i - line)
        children = indent if children is None else min(children, indent)
    else:
        i = len(lines)
    last = max((j for j in range(line, i) if is_content(lines[j])), default=line)
    return sorted({*sizes, last - line + 1})


def _parses_past(lines: list[str], end: int) -> bool:
    """True when ``lines`` parse without error, or the first error is where the cut-off text ends."""
    return _reach(lines) >= end


def _reach(lines: list[str]) -> int:
    """The line (0-based) of the first parse error in ``lines``; ``len(lines)`` when there is none."""
    loader = _FAST_LOADER("\n".join(lines) + "\n")
    try:
        while loader.check_event():
            loader.get_event()
    except yaml.MarkedYAMLError as e:
        mark = e.problem_mark or e.context_mark
        return mark.line if mark is not None else 0
    except yaml.YAMLError:
        return 0
    finally:
        loader.dispose()
    return len(lines)


def _oddness(lines: list[str], style: _Style, starts_file: bool = False) -> int:
    """How unlike a tidy file ``lines`` are: keys (or dashes) with nothing under them, lines
    that continue the one above at a deeper indentation, nesting steps unlike the file's usual
    step, a list at its key's own indentation in a file that never writes one so, and (for
    ``lines`` that start the file) a first line that is indented at all."""
    first = next((line for line in lines if is_content(line)), "")
    odd = int(starts_file and indent_of(first) > 0)
    previous: str | None = None
    for line in lines:
        if not is_content(line):
            continue
        if previous is not None:
            odd += _odd_pair(previous, line, style)
        previous = line
    return odd


def _odd_pair(previous: str, line: str, style: _Style) -> bool:
    deeper = indent_of(line) - content_column(previous)
    if not opens_block(previous):
        return deeper > 0  # continues the text of the line above
    if deeper > 0:
        return deeper != style.step
    indentless = indent_of(line) == indent_of(previous) and is_item(line) and not is_item(previous)
    return not (indentless and style.indentless)  # a key with nothing under it


def _style(lines: list[str], content: list[int], suspects: set[int]) -> _Style:
    """The usual nesting step (how much deeper than its key a block's first line starts) and
    whether lists at their key's indentation occur, judged on the lines that are not suspects."""
    steps: Counter[int] = Counter()
    indentless = False
    for a, b in zip(content, content[1:], strict=False):
        if a not in suspects and b not in suspects and opens_block(lines[a]):
            deeper = indent_of(lines[b]) - content_column(lines[a])
            if deeper > 0:
                steps[deeper] += 1
            indentless |= deeper == 0 and is_item(lines[b]) and not is_item(lines[a])
    return _Style(steps.most_common(1)[0][0] if steps else 2, indentless)


# --- lines ------------------------------------------------------------------------------------------

def is_content(line: str) -> bool:
    stripped = line.strip()
    return bool(stripped) and not stripped.startswith("#")


def indent_of(line: str) -> int:
    return len(line) - len(line.lstrip(" "))


def content_column(line: str) -> int:
    """Where the line's content starts after its list dashes (``- name: x`` -> the column of ``name``)."""
    start = indent_of(line)
    dashes = _DASHES.match(line, start)
    return dashes.end() if dashes else start


def is_item(line: str) -> bool:
    stripped = line.lstrip(" ")
    return stripped == "-" or stripped.startswith("- ")


def opens_block(line: str) -> bool:
    """A key with its value on the following lines, or a dash with nothing after it."""
    body = re.sub(r"\s+#.*$", "", line).rstrip()
    return body.endswith(":") or body.lstrip(" ") == "-"
