"""Pull comments out of ST/ladder text before parsing, keeping them with positions.

Comment characters are replaced by spaces (newlines kept), so every position in the
cleaned text is the same line and column as in the original.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from .nodes import Comment, Span

# Studio 5000 (v32+) folds ST with `#region name` ... `#endregion` lines; they are no
# statements and the controller ignores them, so they are blanked like comments.
_REGION = re.compile(r"^[ \t]*#(?:end)?region(?![A-Za-z0-9_])[^\n]*", re.MULTILINE | re.IGNORECASE)


@dataclass(slots=True)
class Stripped:
    text: str
    comments: list[Comment]
    unterminated: list[Span]  # comments or strings that never close


def _pos(text: str, offset: int, line_starts: list[int]) -> tuple[int, int]:
    lo, hi = 0, len(line_starts) - 1
    while lo < hi:
        mid = (lo + hi + 1) // 2
        if line_starts[mid] <= offset:
            lo = mid
        else:
            hi = mid - 1
    return lo + 1, offset - line_starts[lo] + 1


def line_starts(text: str) -> list[int]:
    starts = [0]
    find = text.find
    i = find("\n")
    while i >= 0:
        starts.append(i + 1)
        i = find("\n", i + 1)
    return starts


def strip_comments(text: str) -> Stripped:
    """Replace `//`, `(* *)` and `/* */` comments and `#region` lines by blanks; strings are
    left alone."""
    if "#" in text and _REGION.search(text):
        text = _REGION.sub(lambda m: " " * len(m.group()), text)
    # Fast path: nothing that can start a comment.
    if "//" not in text and "(*" not in text and "/*" not in text:
        return Stripped(text, [], [])
    out: list[str] = []
    comments: list[Comment] = []
    unterminated: list[Span] = []
    starts = line_starts(text)
    i, n, last = 0, len(text), 0
    while i < n:
        ch = text[i]
        if ch == "'" or ch == '"':
            j = i + 1
            while j < n and text[j] != ch and text[j] != "\n":
                j += 2 if text[j] == "$" else 1
            i = j + 1
            continue
        two = text[i : i + 2]
        if two == "//":
            j = text.find("\n", i)
            j = n if j < 0 else j
        elif two == "(*" or two == "/*":
            close = "*)" if two == "(*" else "*/"
            j = text.find(close, i + 2)
            if j < 0:
                line, col = _pos(text, i, starts)
                unterminated.append(Span(line, col, line, col + 2))
                j = n
            else:
                j += 2
        else:
            i += 1
            continue
        out.append(text[last:i])
        body = text[i:j]
        out.append("".join("\n" if c == "\n" else " " for c in body))
        line, col = _pos(text, i, starts)
        eline, ecol = _pos(text, j, starts) if j < n else _pos(text, n, starts)
        comments.append(Comment(body, Span(line, col, eline, ecol)))
        last = i = j
    out.append(text[last:])
    return Stripped("".join(out), comments, unterminated)
