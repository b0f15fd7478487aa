"""YAML syntax errors in plain words, at the line that is wrong.

PyYAML's messages are parser words ("expected <block end>, but found '<block mapping start>'")
at the place the parser got stuck, which for an indentation mistake is often a later line. For
the problems an indentation mistake causes, :func:`stuart_bt.tree.yaml_indent.find_fix` finds
the line to blame and the message says how far it is indented and how far it should be; when
no re-indentation helps, the problem is still said in words (a ':' inside an unquoted value, a
key without ':', a list item among keys). Other syntax errors keep PyYAML's words, at its mark.
"""

from __future__ import annotations

import yaml

from .errors import TreeError
from .spec import Location
from .yaml_indent import Fix, content_column, find_fix, indent_of, is_content, is_item

# The parser problems an indentation mistake produces (PyYAML's words, then libyaml's).
STRUCTURE_PROBLEMS = (
    "expected <block end>",
    "mapping values are not allowed",
    "could not find expected ':'",
    "expected '<document start>'",
    "did not find expected key",
    "did not find expected '-' indicator",
    "block sequence entries are not allowed",
)

def syntax_error(e: yaml.MarkedYAMLError, text: str, file: str) -> TreeError:
    """One error for a YAML syntax problem: its place, and what is wrong in words."""
    mark = e.problem_mark or e.context_mark
    if mark is None:
        return TreeError(Location(file, 1, 1), f"YAML syntax error: {e.problem or e}")
    lines = text.splitlines()
    tab = _tab_error(lines, mark, file)
    if tab is not None:
        return tab
    problem = e.problem or ""
    if any(p in problem for p in STRUCTURE_PROBLEMS):
        return _structure_error(e, lines, file)
    return TreeError(Location(file, mark.line + 1, mark.column + 1), f"YAML syntax error: {_parser_words(e, mark)}")


def _parser_words(e: yaml.MarkedYAMLError, mark: yaml.Mark) -> str:
    detail = e.problem or "invalid YAML"
    if e.context:
        detail = f"{detail} ({e.context}"
        if e.context_mark is not None and e.context_mark is not mark:
            detail += f" at line {e.context_mark.line + 1}, column {e.context_mark.column + 1}"
        detail += ")"
    return detail


def _tab_error(lines: list[str], mark: yaml.Mark, file: str) -> TreeError | None:
    line = lines[mark.line] if mark.line < len(lines) else ""
    if line[mark.column:mark.column + 1] != "\t":
        return None
    what = "for indentation" if not line[:mark.column].strip() else "here"
    return TreeError(Location(file, mark.line + 1, mark.column + 1),
                     f"tab characters are not allowed {what}; use spaces")


def _structure_error(e: yaml.MarkedYAMLError, lines: list[str], file: str) -> TreeError:
    mark = e.problem_mark or e.context_mark
    assert mark is not None
    context = e.context_mark.line if e.context_mark is not None and e.context_mark.line < mark.line else None
    if "could not find expected ':'" in (e.problem or "") and context is not None and ":" not in lines[context]:
        return _described(e, mark, lines, file)  # a key without its ':', not a line out of place
    fix = find_fix(lines, mark.line, context)
    if fix is not None:
        return TreeError(Location(file, fix.line + 1, fix.old + 1), describe_fix(fix, lines))
    return _mixed_block(lines, mark.line, file) or _described(e, mark, lines, file)


def _mixed_block(lines: list[str], problem: int, file: str) -> TreeError | None:
    """A list item lined up with keys, or a key lined up with list items: the indentation is
    consistent, the block is not (YAML has no block that is both a mapping and a list)."""
    content = [i for i, line in enumerate(lines) if is_content(line)]
    if problem not in content or content.index(problem) == 0:
        return None
    above = content[content.index(problem) - 1]
    line, other = lines[problem], lines[above]
    if indent_of(line) != indent_of(other) or is_item(line) == is_item(other):
        return None
    what, them = ("a list item", "keys") if is_item(line) else ("a key", "list items ('- ...')")
    fix = "put the list under a key of its own" if is_item(line) else "make it a list item or move it out of the list"
    return TreeError(Location(file, problem + 1, indent_of(line) + 1),
                     f"{_shown(line)} is {what}, but it lines up with {them} like {_shown(other)} on line "
                     f"{above + 1}: one block is either all keys or all list items; {fix}")


def describe_fix(fix: Fix, lines: list[str]) -> str:
    """What is wrong with the line ``fix`` moves, and where it should start."""
    moved = fix.apply(lines)
    what = f"wrong indentation: {_shown(lines[fix.line])} is indented {_spaces(fix.old)}"
    rest = f" (with the {fix.count - 1} line{'s' if fix.count > 2 else ''} under it)" if fix.count > 1 else ""
    to = f"indent it{rest} {_spaces(fix.new)}" if fix.new else f"start it{rest} at the beginning of the line"
    sibling = _sibling(moved, fix.line, fix.new)
    if sibling is not None:
        kind = "list item" if is_item(lines[fix.line]) else "key"
        where = f"are indented {fix.new}" if indent_of(lines[sibling]) == fix.new else f"start {fix.new} spaces in"
        return (f"{what}, but the {kind}s it belongs with, like {_shown(_from_column(lines[sibling], fix.new))} "
                f"on line {sibling + 1}, {where}; {to}")
    parent = _parent(moved, fix.line, fix.new)
    if parent is not None:
        deeper = fix.new - content_column(lines[parent])
        return f"{what}, so it is not under {_shown(lines[parent])} on line {parent + 1}; {to}, {deeper} more"
    return f"{what}; {to}"


def _sibling(lines: list[str], line: int, indent: int) -> int | None:
    """The nearest other line in the same block as ``line`` that starts at column ``indent``
    (a key may line up with the first key of a list item: ``- speak: hi`` then ``name: x``)."""
    item = is_item(lines[line])
    for direction in (-1, 1):
        i = line + direction
        while 0 <= i < len(lines):
            if is_content(lines[i]):
                if indent_of(lines[i]) == indent and is_item(lines[i]) == item:
                    return i
                if not item and content_column(lines[i]) == indent and indent_of(lines[i]) < indent:
                    return i
                if indent_of(lines[i]) < indent:
                    break
            i += direction
    return None


def _from_column(line: str, column: int) -> str:
    """``line`` from ``column`` on, or all of it when that would cut it short."""
    return line[column:] if line[:column].strip(" -") == "" and column < len(line) else line


def _parent(lines: list[str], line: int, indent: int) -> int | None:
    """The line above ``line`` that a line starting at ``indent`` belongs under."""
    for i in range(line - 1, -1, -1):
        if is_content(lines[i]) and content_column(lines[i]) < indent:
            return i
    return None


def _described(e: yaml.MarkedYAMLError, mark: yaml.Mark, lines: list[str], file: str) -> TreeError:
    """The structure problem in words, when no re-indentation explains it."""
    problem = e.problem or ""
    here = Location(file, mark.line + 1, mark.column + 1)
    if "mapping values are not allowed" in problem:
        return TreeError(here, "':' followed by a space starts a key, which cannot start here: put text that "
                               "holds ': ' in quotes, or start the key on its own line, lined up with its neighbours")
    if "could not find expected ':'" in problem and e.context_mark is not None:
        start = e.context_mark
        words = _shown(lines[start.line]) if start.line < len(lines) else "this line"
        return TreeError(Location(file, start.line + 1, start.column + 1),
                         f"{words} stands where a key is expected but has no ':' after it; write 'key: value', "
                         f"or indent it further if it continues the value above")
    line = lines[mark.line] if mark.line < len(lines) else ""
    block = e.context_mark
    if block is not None and block.line < len(lines) and is_content(line):
        return TreeError(Location(file, mark.line + 1, indent_of(line) + 1),
                         f"wrong indentation: {_shown(line)} is indented {_spaces(indent_of(line))}, which lines up "
                         f"with nothing it can belong to (the block from line {block.line + 1} starts at "
                         f"{_spaces(block.column)}); line it up with the keys or list items it belongs with")
    return TreeError(here, f"YAML syntax error: {_parser_words(e, mark)}")


def _shown(line: str) -> str:
    text = line.strip()
    return repr(text if len(text) <= 40 else text[:37] + "...")


def _spaces(n: int) -> str:
    return f"{n} space{'' if n == 1 else 's'}"
