"""Tag data forms of real exports (decision 0045; fixture tag_data.L5X).

Date/Time values are worked by hand: days since 1970-01-01 (365 a year plus one per leap
year passed), times 86,400 s, plus the time of day, in microseconds (DT#) or nanoseconds
(LDT#).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from interpreter.cli import main
from interpreter.syntax.l5x_data import parse_date_time, parse_value

FIXTURE = Path(__file__).parent / "fixtures" / "tag_data.L5X"


def test_tag_data_fixture_checks_clean(capsys: pytest.CaptureFixture[str]) -> None:
    capsys.readouterr()
    assert main(["check", str(FIXTURE)]) == 0
    assert capsys.readouterr().out.strip() == "0 error(s), 0 warning(s)"


def watch(capsys: pytest.CaptureFixture[str], *names: str) -> dict[str, object]:
    argv = ["run", str(FIXTURE), "--scans", "0", "--json"]
    for w in names:
        argv += ["--watch", w]
    capsys.readouterr()
    assert main(argv) == 0
    return json.loads(capsys.readouterr().out)["tags"]  # type: ignore[no-any-return]


def test_date_time_lint_data_is_microseconds_since_1970(
    capsys: pytest.CaptureFixture[str],
) -> None:
    tags = watch(
        capsys, "Stamps[0]", "Stamps[1]", "Stamps[2]", "L5kStamps[0]", "L5kStamps[1]", "Started"
    )
    # 2022-02-22 06:00: 52 years (1970-2021) with 13 leap days = 18,993 days, + 31 (Jan)
    # + 21 (Feb) = 19,045 days; 19,045 * 86,400 + 6 * 3,600 = 1,645,509,600 s
    assert tags["Stamps[0]"] == 1_645_509_600_000_000
    assert tags["Stamps[1]"] == 0  # the epoch itself
    # 2000-01-01: 30 years with 7 leap days = 10,957 days = 946,684,800 s; + 0.123456 s
    assert tags["Stamps[2]"] == 946_684_800_123_456
    # from L5K data alone: 1970-01-02 00:00:01.0005 = 86,401 s + 500 us
    assert tags["L5kStamps[0]"] == 86_401_000_500
    assert tags["L5kStamps[1]"] == -1_000_000  # one second before the epoch
    # 2024-03-01 12:30:15.25: 54 years with 13 leap days = 19,723 days, + 31 + 29 (2024 is a
    # leap year) = 19,783 days = 1,709,251,200 s; + 45,015 s = 1,709,296,215 s
    assert tags["Started"] == 1_709_296_215_250_000


def test_date_time_ns_radix_is_nanoseconds(capsys: pytest.CaptureFixture[str]) -> None:
    assert watch(capsys, "StartedNs") == {"StartedNs": 1_000_000_001}


def test_string_arrays_from_raw_bytes_and_string_format(
    capsys: pytest.CaptureFixture[str],
) -> None:
    tags = watch(
        capsys,
        "Names[0]",
        "Names[1]",
        "Names[2]",
        "Names[2].LEN",
        "Days[0]",
        "Days[1]",
        "Days[1].LEN",
        "OnlyFirst[0]",
        "OnlyFirst[1]",
    )
    assert tags == {
        "Names[0]": "Pump",
        "Names[1]": "",
        "Names[2]": "Valve 7",
        "Names[2].LEN": 7,
        "Days[0]": "Mon",  # STRING_8: 4 + 8 bytes per element
        "Days[1]": "Tuesday",
        "Days[1].LEN": 7,
        "OnlyFirst[0]": "Alpha",  # without raw bytes only element [0] is known
        "OnlyFirst[1]": "",
    }


def test_parse_date_time_forms() -> None:
    # local midnight at UTC-05:00 is 05:00 UTC: 5 * 3,600 s
    assert parse_date_time("DT#1970-01-01-00:00:00.000_000(UTC-05:00)") == 18_000_000_000
    assert parse_date_time("DT#1970-01-01-00:00:00Z") == 0  # no fraction
    assert parse_date_time("DT#1970-01-01-00:00:00.5Z") == 500_000  # a short fraction
    assert parse_date_time("LDT#1970-01-01-00:00:00.000_000_123Z") == 123
    assert parse_date_time("DT#1970-13-01-00:00:00.000_000Z") is None  # no month 13
    assert parse_date_time("DT#1970-01-01-00:00:00.000_000_1Z") is None  # 7 digits for DT#
    assert parse_date_time("DT#yesterday") is None


def test_non_finite_reals_as_v17_exports_print_them() -> None:
    # LD_Scale_Value.L5X (v17): raw bytes 16#7F80_0000 (+INF) are shown as `1.$`,
    # 16#FFC0_0000 (a NaN) as `-1.#IND`, 16#7F80_0001 (a NaN) as `1.#QNAN`
    assert parse_value("1.$", "Float", "REAL") == math.inf
    assert parse_value("-1.$", "Float", "REAL") == -math.inf
    assert math.isnan(parse_value("-1.#IND", "Float", "REAL"))  # type: ignore[arg-type]
    assert math.isnan(parse_value("1.#QNAN", "Float", "REAL"))  # type: ignore[arg-type]
    assert parse_value("-1.#INF", "Float", "REAL") == -math.inf
