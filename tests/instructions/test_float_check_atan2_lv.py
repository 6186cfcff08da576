"""IsINF / IsNAN (rung and ST function), ATAN2 (rung and two-argument function), LV, and
the instructions with nothing to act on (UID, UIE, IOT)."""

from __future__ import annotations

import math

import pytest

from interpreter.instructions import control_noop, float_check, functions, ladder_math
from interpreter.semantics.types import LREAL, REAL
from interpreter.vm.context import ExecContext
from interpreter.vm.refs import Ref
from interpreter.vm.values import f32


def test_isinf_isnan_rung_conditions() -> None:
    ctx = ExecContext()
    assert float_check.isinf_rung(ctx, True, math.inf) is True
    assert float_check.isinf_rung(ctx, True, -math.inf) is True
    assert float_check.isinf_rung(ctx, True, 3.4e38) is False  # largest REAL is finite
    assert float_check.isinf_rung(ctx, False, math.inf) is False  # false rung stays false
    assert float_check.isnan_rung(ctx, True, math.nan) is True
    assert float_check.isnan_rung(ctx, True, math.inf) is False


def test_isinf_isnan_are_bool_functions_in_structured_text(st) -> None:  # noqa: ANN001
    src = """
    VAR r, z : REAL; i, n, f : BOOL; END_VAR
    r := 1.0 / z;
    i := IsINF(r);
    n := IsNAN(r);
    f := IsNAN(z / z) AND NOT IsINF(z);
    """
    r = st.run(src, "i", "n", "f")
    # 1/0 = +inf: i true, n false; 0/0 = NaN: IsNAN true, IsINF(0) false
    assert r.tags == {"i": True, "n": False, "f": True}


def test_isinf_in_ladder(st) -> None:  # noqa: ANN001
    src = """
    VAR r, z : REAL; hit : BOOL; END_VAR
    DIV(1.0,z,r);
    IsINF(r)OTE(hit);
    """
    assert st.run(src, "hit", name="main.rll").tags == {"hit": True}


def test_atan2_quadrants() -> None:
    ctx = ExecContext()
    assert functions.atan2(ctx, True, 1.0, 1.0) == pytest.approx(math.pi / 4)  # 45 deg
    assert functions.atan2(ctx, True, 1.0, -1.0) == pytest.approx(3 * math.pi / 4)  # 135 deg
    assert functions.atan2(ctx, True, -1.0, -1.0) == pytest.approx(-3 * math.pi / 4)
    assert functions.atan2(ctx, True, 0.0, 0.0) == 0.0


def test_atan2_rung_stores_real_or_lreal() -> None:
    ctx, d = ExecContext(), Ref([0.0], 0, REAL)
    ladder_math.atan2_rung(ctx, True, 1, 0, d)  # (x 0, y 1): straight up, pi/2
    assert d.get() == f32(math.pi / 2)
    ctx, d = ExecContext(), Ref([0.0], 0, LREAL)
    ladder_math.atan2_rung(ctx, True, -1, 0, d)
    assert d.get() == -math.pi / 2


def test_atan2_two_argument_function_in_st_and_cpt(st) -> None:  # noqa: ANN001
    src = """
    VAR y, x, a : REAL; END_VAR
    y := 1.0; x := -1.0;
    a := ATAN2(y, x) * 4.0;
    """
    # atan2(1, -1) = 3*pi/4; times 4 = 3*pi = 9.42477... (REAL)
    assert st.run(src, "a").tags["a"] == pytest.approx(3 * math.pi, rel=1e-6)
    rung = """
    VAR a : REAL; b : REAL; END_VAR
    CPT(a, ATAN2(0.0, -2.0));
    ATAN2(-3.0, 0.0, b);
    """
    t = st.run(rung, "a", "b", name="main.rll").tags
    assert t["a"] == pytest.approx(math.pi) and t["b"] == pytest.approx(-math.pi / 2)


def test_atan2_argument_count_is_checked(st) -> None:  # noqa: ANN001
    r = st.check("VAR a : REAL; END_VAR\na := ATAN2(1.0);\n")
    assert [d["code"] for d in r.json] == ["E104"]


def test_lv_is_false_without_licenses(st) -> None:  # noqa: ANN001
    assert control_noop.lv(ExecContext(), True, 42, 7) is False
    src = """
    VAR ok : BOOL; END_VAR
    OTL(ok);
    LV(1,1)OTE(ok);
    """
    assert st.run(src, "ok", name="main.rll").tags == {"ok": False}


def test_uid_uie_iot_change_nothing(st) -> None:  # noqa: ANN001
    src = """
    VAR n : DINT; out : DINT; END_VAR
    UID();
    n := n + 1;
    UIE();
    IOT(out);
    """
    assert st.run(src, "n", "out", scans=3).tags == {"n": 3, "out": 0}
