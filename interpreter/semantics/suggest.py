"""Did-you-mean at a bounded cost (decision 0055).

Comparing every undefined name with every tag in scope costs undefined names x tags
SequenceMatcher runs: on a large export that was most of `check`. A NameIndex is built once
per pool of names and answers each query from a few candidates:
- typos (one character dropped, added, changed, or two swapped) are found exactly through a
  deletion index: every name and every copy of it with one character removed is a key; a
  query looks up itself and its own one-deletion copies (about its length in lookups);
- otherwise the names with the same first letter and a length within 2 are tried, at most
  FALLBACK_CAP of them.
The few candidates are ranked with difflib's ratio (cutoff 0.6, as before), so a short
list gives the answer difflib alone would give.
"""

from __future__ import annotations

import difflib

CUTOFF = 0.6
FALLBACK_CAP = 24  # names compared when no typo-distance candidate exists
KEY_CAP = 8  # names kept per deletion key (generated names share many keys)
LENGTH_WINDOW = 2


def _deletions(word: str) -> list[str]:
    return [word[:i] + word[i + 1 :] for i in range(len(word))]


class NameIndex:
    def __init__(self, names: list[str]) -> None:
        self.original: dict[str, str] = {}  # lower case -> first spelling seen
        self.keys: dict[str, list[str]] = {}  # name or one-deletion copy -> lower-case names
        self.buckets: dict[tuple[str, int], list[str]] = {}  # (first letter, length) -> names
        for name in names:
            low = name.lower()
            if not low or low in self.original:
                continue
            self.original[low] = name
            for k in (low, *_deletions(low)):
                held = self.keys.setdefault(k, [])
                if len(held) < KEY_CAP and (not held or held[-1] != low):
                    held.append(low)
            self.buckets.setdefault((low[0], len(low)), []).append(low)
        self.cache: dict[str, str | None] = {}

    def best(self, word: str) -> str | None:
        """The closest name (as spelled where declared), or None when nothing is close."""
        low = word.lower()
        if low in self.cache:
            return self.cache[low]
        found: dict[str, None] = {}  # ordered set: the answer must not depend on hashing
        for k in (low, *_deletions(low)):
            for cand in self.keys.get(k, ()):
                found[cand] = None
        candidates = list(found)
        if not candidates and low:
            for dl in (0, -1, 1, -2, 2):
                candidates.extend(self.buckets.get((low[0], len(low) + dl), ()))
                if len(candidates) >= FALLBACK_CAP:
                    break
            candidates = candidates[:FALLBACK_CAP]
        close = difflib.get_close_matches(low, candidates, n=1, cutoff=CUTOFF)
        answer = self.original[close[0]] if close else None
        self.cache[low] = answer
        return answer
