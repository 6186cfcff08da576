"""MAVE (moving average) and MSTD (moving standard deviation), 1756-RM006 statistical
blocks over a user storage array; decision 0179.

- The storage array is a shift register of the last NumberOfSamples samples: element 0 holds
  the newest, element N-1 the oldest; each sample shifts the others one place up and the
  oldest falls out. MAVE's WeightArray[i] weights the sample i executions old.
- A sample of In is taken at each execution while SampleEnable is set and InFault is clear
  (a faulted input is not averaged in; InFaulted reports it). Out is recomputed from the
  stored samples every execution.
- Initialize, and the first execution after prescan (instruction first scan), fill the N
  storage elements with In, so the outputs start at In (MSTD's spread at 0) instead of
  averaging whatever the array held.
- NumberOfSamples must be at least 1 and fit the storage array (and, with UseWeights, the
  weight array); otherwise NumberOfSampInv and InstructFault are set and the outputs hold.
- MAVE: Out = sum(In_i) / N, or sum(W_i x In_i) with UseWeights (the weights are the user's:
  they are not normalised). MSTD: Average = sum(In_i) / N and Out the sample standard
  deviation sqrt(sum((In_i - Average)^2) / (N - 1)), 0 for one sample: the same estimator as
  the ladder STD file instruction.
- Sums in double precision (math.fsum); outputs rounded to REAL; EnableOut drops when an
  output overflows to an infinity.
"""

from __future__ import annotations

import math

from ..runtime.motion_layout import packed_words, struct_type
from ..vm.context import ExecContext
from ..vm.refs import ArrayRef
from ..vm.values import f32
from .process_blocks import pack_status
from .registry import implements, prescan

_AV = struct_type("MOVING_AVERAGE").index
_AV_WORDS = packed_words("MOVING_AVERAGE")
_SD = struct_type("MOVING_STD_DEV").index
_SD_WORDS = packed_words("MOVING_STD_DEV")


def _samples(
    s: list, ix: dict[str, int], words: tuple, storage: ArrayRef, limit: int
) -> list[float] | None:
    """Validate NumberOfSamples, take this execution's sample and return the N stored samples
    (newest first), or None when NumberOfSamples is invalid (Status set, outputs held)."""
    n = s[ix["NUMBEROFSAMPLES"]]
    invalid = not 1 <= n <= limit
    s[ix["INFAULTED"]] = int(bool(s[ix["INFAULT"]]))
    s[ix["NUMBEROFSAMPINV"]] = s[ix["INSTRUCTFAULT"]] = int(invalid)
    pack_status(s, words)
    if invalid:
        s[ix["ENABLEOUT"]] = 1
        return None
    x = s[ix["IN"]]
    if s[ix["INITIALIZE"]] or not s[ix["STORAGELOADED"]]:
        for i in range(n):
            storage.set(i, x)
        s[ix["STORAGELOADED"]] = 1
    elif s[ix["SAMPLEENABLE"]] and not s[ix["INFAULT"]]:
        for i in range(n - 1, 0, -1):
            storage.set(i, storage.get(i - 1))
        storage.set(0, x)
    return [float(storage.get(i)) for i in range(n)]  # type: ignore[arg-type]


@implements("MAVE")
def mave(
    ctx: ExecContext, rung: bool, s: list, storage: ArrayRef, weights: ArrayRef | None = None
) -> None:
    # the WeightArray operand is optional (an unweighted average needs none); weighting with
    # no weights is treated as a weight array too small for any NumberOfSamples
    limit = len(storage)
    if s[_AV["USEWEIGHTS"]]:
        limit = min(limit, len(weights) if weights is not None else 0)
    values = _samples(s, _AV, _AV_WORDS, storage, limit)
    if values is None:
        return
    if s[_AV["USEWEIGHTS"]] and weights is not None:
        out = math.fsum(float(weights.get(i)) * v for i, v in enumerate(values))  # type: ignore[arg-type]
    else:
        out = math.fsum(values) / len(values)
    s[_AV["OUT"]] = o = f32(out)
    s[_AV["ENABLEOUT"]] = int(not math.isinf(o))


@implements("MSTD")
def mstd(ctx: ExecContext, rung: bool, s: list, storage: ArrayRef) -> None:
    values = _samples(s, _SD, _SD_WORDS, storage, len(storage))
    if values is None:
        return
    n = len(values)
    mean = math.fsum(values) / n
    spread = math.fsum((v - mean) ** 2 for v in values)
    s[_SD["AVERAGE"]] = avg = f32(mean)
    s[_SD["OUT"]] = out = f32(math.sqrt(spread / (n - 1)) if n > 1 else 0.0)
    s[_SD["ENABLEOUT"]] = int(not (math.isinf(avg) or math.isinf(out)))


@prescan("MAVE")
def mave_prescan(ctx: ExecContext, rung: bool, s: list, *arrays: ArrayRef) -> None:
    s[_AV["STORAGELOADED"]] = 0  # the first execution fills the storage with In


@prescan("MSTD")
def mstd_prescan(ctx: ExecContext, rung: bool, s: list, *arrays: ArrayRef) -> None:
    s[_SD["STORAGELOADED"]] = 0
