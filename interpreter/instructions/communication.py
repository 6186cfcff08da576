"""MSG, the ASCII serial-port instructions and HMIBC on a controller with nothing connected.

SPEC 9.32 and decision 0035. Nothing in logixst answers a message or sends a character, so
these instructions show what a controller shows when the far end is missing.

MSG (1756-RM003), state in the MESSAGE's bits. The controller moves a message on by itself,
asynchronously to the logic: logixst does it at the start of every scan (ctx.background) and
when the instruction executes, in virtual time:
- start (ladder: true rung with EN clear; ST: EN clear, or DN/ER set from the last run):
  EN and EW set, ST DN ER cleared, ERR EXERR DN_LEN zeroed, the time remembered.
- a later execution: the request has been sent: EW cleared, ST set.
- once UnconnectedTimeout (microseconds; 0 or negative: the 30 s default) has passed since
  the start: ST cleared, ER set, ERR = connection failure 16#0001 and EXERR = unconnected
  request timed out 16#0204 (numbers from the MSG_ERR / MSG_EXERR catalog enumerations).
- the program setting TO stops a pending message: ER (ERR left 0).
- ladder false rung: EN is cleared once DN or ER is set; a pending message keeps running.

ASCII (1756-RM003 ASCII chapter). Channel 0 is the controller's serial port; another channel
is an error (ER). Ladder calls come on the rung's rising edge (catalog: transitional) and on
false rungs, which clear EN of a finished request. In ST a call starts a request when EN is
clear or the previous one finished (DN or ER), and does nothing while one is pending.
- ABL / ACB: the receive buffer is always empty: DN, POS 0, FD clear.
- AHL: driving DTR/RTS needs no partner: DN.
- AWT / AWA: the port transmits to an idle line: DN with POS = characters sent: LEN, or
  the STRING's own LEN when LEN is 0 (AWA adds the two default append characters $r$l).
  LEN above the source's size or negative: ER.
- ARD / ARL: no character arrives, so the request waits for ever: EU, and RN for the first
  read on the port (one read runs at a time; later ones wait in the queue with EU only).
  ACL with ClearSerialPortRead removes them: EU and RN cleared, ER set. LEN <= 0 or above
  the destination's size: ER.
- EU stays set from the start of a request until the next one; EM and UL are not used.
Ladder display operands (length, characters read/sent) given as numbers are written into
.LEN at prescan like the Preset of a timer (decision 0030); `?` leaves .LEN alone.
"""

from __future__ import annotations

from stdlib import catalog

from ..vm.context import ExecContext
from ..vm.refs import ArrayRef
from .fbd_timers import _layout
from .ladder_timers_counters import apply_pseudo
from .registry import implements, prescan

# ------------------------------------------------------------------ MSG
_M = _layout("MESSAGE")
M_EW, M_ER, M_DN, M_ST, M_EN = _M["EW"], _M["ER"], _M["DN"], _M["ST"], _M["EN"]
M_ERR, M_EXERR, M_DN_LEN = _M["ERR"], _M["EXERR"], _M["DN_LEN"]
M_TIMEOUT, M_SENT, M_TO = _M["UNCONNECTEDTIMEOUT"], _M["SENTTIME"], _M["TO"]

DEFAULT_TIMEOUT_MS = 30_000.0  # UnconnectedTimeout's documented default, 30 s


def _code(enum: str, text: str) -> int:
    v = catalog().enum(enum).lookup(text)
    assert v is not None, (enum, text)
    return v.value


CONNECTION_FAILURE = _code("MSG_ERR", "Connection failure")
UNCONNECTED_TIMEOUT = _code("MSG_EXERR", "Unconnected request timed out")


class _Transfers:
    """The messages in progress; the controller moves them on at the start of every scan
    whether or not the program executes their MSG again (the bits change asynchronously)."""

    __slots__ = ("pending",)

    def __init__(self) -> None:
        self.pending: list[list] = []

    def __call__(self, ctx: ExecContext) -> None:
        for m in list(self.pending):
            _msg_advance(ctx, m)
            if not m[M_EN] or m[M_DN] or m[M_ER]:
                self.pending.remove(m)


def _msg_start(ctx: ExecContext, m: list) -> None:
    m[M_EN] = m[M_EW] = 1
    m[M_ST] = m[M_DN] = m[M_ER] = 0
    m[M_ERR] = m[M_EXERR] = m[M_DN_LEN] = 0
    m[M_SENT] = ctx.now_ms
    transfers = ctx.background.setdefault("MSG", _Transfers())
    if not any(p is m for p in transfers.pending):
        transfers.pending.append(m)


def _msg_advance(ctx: ExecContext, m: list) -> None:
    """Move a pending message on: sent after its first scan, failed after the timeout or
    when the program sets TO."""
    if not m[M_EN] or m[M_DN] or m[M_ER]:
        return
    if m[M_TO]:  # the program stops the message: ER (the manual gives no code for it)
        m[M_EW] = m[M_ST] = 0
        m[M_ER] = 1
        return
    elapsed = ctx.now_ms - m[M_SENT]
    if elapsed <= 0:
        return
    m[M_EW] = 0
    m[M_ST] = 1
    timeout = m[M_TIMEOUT] / 1000.0 if m[M_TIMEOUT] > 0 else DEFAULT_TIMEOUT_MS
    if elapsed + 1e-9 >= timeout:
        m[M_ST] = 0
        m[M_ER] = 1
        m[M_ERR] = CONNECTION_FAILURE
        m[M_EXERR] = UNCONNECTED_TIMEOUT


@implements("MSG@rll")
def msg_ladder(ctx: ExecContext, rung: bool, m: list) -> None:
    if rung and not m[M_EN]:
        _msg_start(ctx, m)
        return
    _msg_advance(ctx, m)
    if not rung and (m[M_DN] or m[M_ER]):
        m[M_EN] = 0


@implements("MSG@st")
def msg_st(ctx: ExecContext, rung: bool, m: list) -> None:
    if not m[M_EN] or m[M_DN] or m[M_ER]:
        _msg_start(ctx, m)
        return
    _msg_advance(ctx, m)


# ------------------------------------------------------------------ ASCII
_A = _layout("SERIAL_PORT_CONTROL")
A_LEN, A_POS, A_EN, A_EU, A_DN = _A["LEN"], _A["POS"], _A["EN"], _A["EU"], _A["DN"]
A_RN, A_ER, A_FD = _A["RN"], _A["ER"], _A["FD"]
APPEND_CHARS = 2  # AWA's default append characters: carriage return, line feed
_READS = "ascii_pending_reads"  # ctx.system key: the read requests waiting on the port


def _pending(ctx: ExecContext) -> list[list]:
    return ctx.system.setdefault(_READS, [])  # type: ignore[no-any-return]


def _begin(ctx: ExecContext, rung: bool, c: list, channel: int) -> bool:
    """Common entry: False when this call does not start a new request."""
    if not rung:  # ladder false rung: re-arm a finished request
        if c[A_DN] or c[A_ER]:
            c[A_EN] = 0
        return False
    if c[A_EN] and not (c[A_DN] or c[A_ER]):
        return False  # still pending
    c[A_EN] = c[A_EU] = 1
    c[A_DN] = c[A_ER] = c[A_RN] = c[A_FD] = 0
    if channel != 0:
        c[A_ER] = 1  # the controller has one serial port, channel 0
        return False
    return True


def _size(v: object) -> tuple[int, int | None]:
    """(capacity in characters, a STRING's own LEN or None) of a source or destination: a
    STRING, or the array walked from the given element (memory operand, an ArrayRef)."""
    if isinstance(v, ArrayRef):
        first = v.get(0) if len(v) > 0 else None
        if isinstance(first, list):  # a STRING tag, or an element of a STRING array
            return _size(first)
        return (len(v) if v.dims else 1), None
    assert isinstance(v, list)
    if len(v) == 2 and isinstance(v[1], list):  # STRING-like: LEN, DATA[]
        return len(v[1]), int(v[0])
    return len(v), None


@implements("ABL", "ACB")
def count_buffer(ctx: ExecContext, rung: bool, ch: int, c: list, display: object = None) -> None:
    if _begin(ctx, rung, c, ch):
        c[A_POS] = 0  # nothing ever arrives: the receive buffer is empty
        c[A_DN] = 1


@implements("AHL")
def handshake(
    ctx: ExecContext,
    rung: bool,
    ch: int,
    and_mask: int,
    or_mask: int,
    c: list,
    display: object = None,
) -> None:
    if _begin(ctx, rung, c, ch):
        c[A_DN] = 1


def _write(ctx: ExecContext, rung: bool, ch: int, src: object, c: list, extra: int) -> None:
    if not _begin(ctx, rung, c, ch):
        return
    size, own = _size(src)
    length = c[A_LEN] if c[A_LEN] != 0 or own is None else own
    if not 0 <= length <= size:
        c[A_ER] = 1
        return
    c[A_POS] = length + extra
    c[A_DN] = 1


@implements("AWT")
def awt(ctx: ExecContext, rung: bool, ch: int, src: object, c: list, *display: object) -> None:
    _write(ctx, rung, ch, src, c, 0)


@implements("AWA")
def awa(ctx: ExecContext, rung: bool, ch: int, src: object, c: list, *display: object) -> None:
    _write(ctx, rung, ch, src, c, APPEND_CHARS)


@implements("ARD", "ARL")
def read(ctx: ExecContext, rung: bool, ch: int, dest: object, c: list, *display: object) -> None:
    if not _begin(ctx, rung, c, ch):
        return
    if not 0 < c[A_LEN] <= _size(dest)[0]:
        c[A_ER] = 1
        return
    c[A_POS] = 0
    reads = _pending(ctx)
    reads[:] = [r for r in reads if r is not c]
    c[A_RN] = int(not reads)  # only the first read on the port runs; the others queue
    reads.append(c)


@prescan("ARD", "ARL", "AWT", "AWA")
def length_prescan(
    ctx: ExecContext,
    rung: bool,
    ch: int,
    data: object,
    c: list,
    length: object = None,
    *rest: object,
) -> None:
    apply_pseudo(c, ((A_LEN, length),))
    ctx.system.pop(_READS, None)  # a new run starts with an idle port


@implements("ACL")
def acl(ctx: ExecContext, rung: bool, ch: int, clear_read: int, clear_write: int) -> None:
    if not rung or ch != 0:
        return
    if clear_read:
        for c in _pending(ctx):
            c[A_RN] = c[A_EU] = 0
            c[A_ER] = 1
        _pending(ctx).clear()
    # writes never wait (they complete when started), so there is no write queue to clear


# ------------------------------------------------------------------ HMIBC
# An HMI button needs a PanelView 5000 terminal on an I/O connection; none is ever connected
# here, so no press is seen (SPEC 9.32, decision 0151).
_H = _layout("HMIBC")
H_EIN, H_EOUT, H_OUT = _H["ENABLEIN"], _H["ENABLEOUT"], _H["OUT"]


@implements("HMIBC")
def hmibc(ctx: ExecContext, rung: bool, h: list) -> None:
    """EnableIn/EnableOut follow the rung (always true in ST); an executing block reports
    no press: Out 0. ButtonState, BitIndex and TerminalCount belong to the connection and
    are left as they are."""
    h[H_EIN] = h[H_EOUT] = int(rung)
    if rung:
        h[H_OUT] = 0
