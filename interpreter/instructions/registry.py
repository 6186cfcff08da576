"""Instruction implementations, registered by catalog name; the VM dispatches through this.

Calling convention (docs/decisions/0003-vm-design.md): `impl(ctx, rung, *operands)`.
- `ctx`: the ExecContext (virtual time, faults, motion, program data).
- `rung`: the rung condition in (always True in ST); ladder false-rung actions run with False.
- operands, in catalog order: elementary `in` operands as values (int/float); enumerations
  as their number; `out`/`inout` elementary operands as Ref/BitRef; structure operands as
  the structure value itself (a mutable list); `array` operands as ArrayRef; `routine` as the
  routine name; a STRING `in` operand as its structure list.
- return: the rung condition out for ladder input instructions (None = pass `rung` on).
An optional prescan action is registered with `@prescan("NAME")`, same signature.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

Impl = Callable[..., Any]

# Instructions the compilers lower to bytecode themselves: they have no implementation
# function (ladder contacts and coils, compares, MOV, CPT, CMP, FAL, FSC, program control).
LOWERED = frozenset({
    "XIC", "XIO", "OTE", "OTL", "OTU", "EQU", "NEQ", "GRT", "GEQ", "LES", "LEQ", "MOV",
    "JMP", "LBL", "MCR", "AFI", "NOP", "TND", "JSR", "SBR", "RET", "CPT", "CMP", "FAL", "FSC",
})

IMPLEMENTATIONS: dict[str, Impl] = {}
PRESCANS: dict[str, Impl] = {}
_LOADED = False


def implements(*names: str) -> Callable[[Impl], Impl]:
    """Register `fn` as the implementation of catalog instruction keys or names.

    A name is a catalog name (`TONR`) or, where ST and ladder entries share a name,
    `NAME@lang` (`ABS@st`, `ABS@rll`).
    """

    def deco(fn: Impl) -> Impl:
        for name in names:
            IMPLEMENTATIONS[_key(name)] = fn
        return fn

    return deco


def _key(name: str) -> str:
    base, _, lang = name.partition("@")
    return f"{base.upper()}@{lang.lower()}" if lang else base.upper()


def prescan(*names: str) -> Callable[[Impl], Impl]:
    def deco(fn: Impl) -> Impl:
        for name in names:
            PRESCANS[_key(name)] = fn
        return fn

    return deco


def load_all() -> None:
    """Import every implementation module (each registers itself)."""
    import importlib
    import pkgutil

    from .. import instructions

    global _LOADED
    if _LOADED:  # lookups run per call site; scanning the package each time cost seconds on big projects
        return
    for mod in pkgutil.iter_modules(instructions.__path__):
        if mod.name not in ("registry",):
            importlib.import_module(f"{instructions.__name__}.{mod.name}")
    _LOADED = True


def lookup(name: str, language: str) -> Impl | None:
    load_all()
    return IMPLEMENTATIONS.get(f"{name.upper()}@{language}") or IMPLEMENTATIONS.get(name.upper())


def lookup_prescan(name: str, language: str) -> Impl | None:
    load_all()
    return PRESCANS.get(f"{name.upper()}@{language}") or PRESCANS.get(name.upper())
