"""DTR, data transitional (1756-RM003 special instructions; Studio 5000 v37 help).

- Prescan and a false rung: Reference = Source AND Mask, rung-condition-out false.
- True rung: when Source AND Mask differs from Reference, the rung-condition-out is true
  for this execution and Reference takes the masked value; otherwise the rung goes false.
So the rung is true once per change of the watched bits. Math status flags are not touched.
"""

from __future__ import annotations

from ..vm.context import ExecContext
from ..vm.refs import Ref
from ..vm.values import wrap
from .registry import implements, prescan


def _masked(source: int, mask: int) -> int:
    return wrap(int(source) & int(mask), 32, True)


@implements("DTR")
def dtr(ctx: ExecContext, rung: bool, source: int, mask: int, reference: Ref) -> bool:
    value = _masked(source, mask)
    changed = rung and value != reference.get()
    reference.set(value)
    return changed


@prescan("DTR")
def dtr_prescan(ctx: ExecContext, rung: bool, source: int, mask: int, reference: Ref) -> bool:
    reference.set(_masked(source, mask))
    return False
