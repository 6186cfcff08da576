"""Ladder one-shots ONS, OSR, OSF (1756-RM003 bit chapter, Studio 5000 v37 help).

The storage bit remembers the rung condition of the previous execution; the impls receive it
(and OSR/OSF's output bit) as Ref or BitRef.
- ONS is an input instruction: its rung-condition-out is true for exactly one execution
  after the rung rose. OSR and OSF pass the rung on unchanged and pulse their output bit.
- False rung: ONS and OSR clear the storage bit (OSR also the output bit); OSF pulses its
  output if the storage bit was set, then clears the storage bit.
- Prescan (entering Run): ONS and OSR set the storage bit, so a rung that is already true
  does not fire on the first scan; OSF clears it, so a rung that is already false does not
  fire either. OSR and OSF clear the output bit.
"""

from __future__ import annotations

from ..vm.context import ExecContext
from ..vm.refs import BitRef, Ref
from .registry import implements, prescan

Bit = Ref | BitRef


@implements("ONS")
def ons(ctx: ExecContext, rung: bool, storage: Bit) -> bool:
    if not rung:
        storage.set(0)
        return False
    if storage.get():
        return False  # still the same true period: no pulse
    storage.set(1)
    return True


@prescan("ONS")
def ons_prescan(ctx: ExecContext, rung: bool, storage: Bit) -> bool:
    storage.set(1)
    return False


@implements("OSR")
def osr(ctx: ExecContext, rung: bool, storage: Bit, output: Bit) -> None:
    if not rung:
        storage.set(0)
        output.set(0)
        return
    output.set(0 if storage.get() else 1)
    storage.set(1)


@prescan("OSR")
def osr_prescan(ctx: ExecContext, rung: bool, storage: Bit, output: Bit) -> None:
    storage.set(1)
    output.set(0)


@implements("OSF")
def osf(ctx: ExecContext, rung: bool, storage: Bit, output: Bit) -> None:
    if rung:
        storage.set(1)
        output.set(0)
        return
    output.set(1 if storage.get() else 0)  # the rung fell since the last execution
    storage.set(0)


@prescan("OSF")
def osf_prescan(ctx: ExecContext, rung: bool, storage: Bit, output: Bit) -> None:
    storage.set(0)
    output.set(0)
