"""IsINF and IsNAN: ladder input instructions and expression functions returning BOOL
(1756-RM003 compare chapter, 5x80 controllers; decision 0062).

An integer argument is never infinite or NaN; the catalog admits only REAL and LREAL.
"""

from __future__ import annotations

import math

from ..vm.context import ExecContext
from .registry import implements


@implements("ISINF@rll")
def isinf_rung(ctx: ExecContext, rung: bool, x: float) -> bool:
    return rung and math.isinf(x)


@implements("ISNAN@rll")
def isnan_rung(ctx: ExecContext, rung: bool, x: float) -> bool:
    return rung and math.isnan(x)


@implements("ISINF@st")
def isinf_fn(ctx: ExecContext, rung: bool, x: float) -> int:
    return int(math.isinf(x))


@implements("ISNAN@st")
def isnan_fn(ctx: ExecContext, rung: bool, x: float) -> int:
    return int(math.isnan(x))
