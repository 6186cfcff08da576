"""Did-you-mean from a bounded index (semantics/suggest.py, decision 0055)."""

from __future__ import annotations

import pytest

from interpreter.semantics.suggest import FALLBACK_CAP, NameIndex

TAGS = ["Speed", "MotorSpeed", "Conveyor_Run", "Conveyor_Fault", "Tank1Level", "Tank2Level", "x"]


@pytest.mark.parametrize(
    ("typed", "meant"),
    [
        ("Sped", "Speed"),  # a character dropped
        ("Speeed", "Speed"),  # a character added
        ("Spead", "Speed"),  # a character changed
        ("Seped", "Speed"),  # two characters swapped
        ("conveyor_fualt", "Conveyor_Fault"),  # case differs, and a swap
        ("Tank1Levl", "Tank1Level"),
        ("MotorSpd", "MotorSpeed"),  # two characters dropped: found among same-letter names
    ],
)
def test_close_names_are_suggested_as_declared(typed: str, meant: str) -> None:
    assert NameIndex(TAGS).best(typed) == meant


@pytest.mark.parametrize("typed", ["Pressure", "y", "Q", "zzzzzzzzzz"])
def test_nothing_close_gives_no_suggestion(typed: str) -> None:
    assert NameIndex(TAGS).best(typed) is None


def test_same_answer_each_time_and_per_name_cache() -> None:
    index = NameIndex(TAGS)
    assert index.best("Sped") == index.best("SPED") == "Speed"
    assert set(index.cache) == {"sped"}


def test_fallback_looks_at_a_bounded_number_of_names() -> None:
    # 500 names of one first letter and length: a query close to none of them by one edit
    # compares at most FALLBACK_CAP of them, not all 500
    names = [f"a{k:05d}" for k in range(500)]
    index = NameIndex(names)
    compared: list[int] = []
    import difflib

    real = difflib.get_close_matches

    def counting(word, possibilities, n=3, cutoff=0.6):  # type: ignore[no-untyped-def]
        compared.append(len(possibilities))
        return real(word, possibilities, n, cutoff)

    difflib.get_close_matches = counting  # type: ignore[assignment]
    try:
        index.best("azzzzz")
    finally:
        difflib.get_close_matches = real
    assert compared == [FALLBACK_CAP]


def test_check_suggests_the_declared_tag(st) -> None:  # noqa: ANN001
    r = st.check("VAR Speed : REAL; END_VAR\nSped := 1.0;\n", "text")
    assert "E101 undefined tag 'Sped' (did you mean 'Speed'?)" in r.out
