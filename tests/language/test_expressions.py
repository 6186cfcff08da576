"""Operator precedence, logical vs bitwise operators, `**`, literals and comments (SPEC 3.1, 9.13, 9.14)."""

from __future__ import annotations


def test_arithmetic_precedence(st) -> None:
    src = """
    VAR a, b, c, d, e, f, g, h : DINT; END_VAR
    a := -2 ** 2;
    b := 2 + 3 * 4;
    c := (2 + 3) * 4;
    d := 10 - 4 - 3;
    e := 100 / 10 / 5;
    f := 2 ** 3 ** 2;
    g := -2 * -3 + 1;
    h := 7 - 2 * 3 MOD 4;
    """
    t = st.tags(src, *"abcdefgh")
    assert t["a"] == -4  # ** binds tighter than unary minus: -(2 ** 2)
    assert t["b"] == 14  # 2 + (3 * 4)
    assert t["c"] == 20
    assert t["d"] == 3  # left to right: (10 - 4) - 3
    assert t["e"] == 2  # (100 / 10) / 5
    assert t["f"] == 64  # equal ranks left to right: (2 ** 3) ** 2 = 8 ** 2
    assert t["g"] == 7  # (-2) * (-3) + 1
    assert t["h"] == 5  # * and MOD same rank, left to right: (2 * 3) MOD 4 = 2; 7 - 2


def test_not_binds_tighter_than_comparison_and_multiplication(st) -> None:
    src = """
    VAR c1, c2 : BOOL; m, n : DINT; END_VAR
    c1 := NOT 2 > -5;
    c2 := NOT (2 > -5);
    m := NOT 1 * 2;
    n := NOT -1;
    """
    t = st.tags(src, "c1", "c2", "m", "n")
    assert t["c1"] is True  # (NOT 2) > -5: bitwise NOT 2 = -3; -3 > -5
    assert t["c2"] is False  # NOT TRUE
    assert t["m"] == -4  # (NOT 1) * 2 = -2 * 2
    assert t["n"] == 0  # unary minus before NOT: NOT (-1) = 0


def test_logical_precedence_and_or_xor(st) -> None:
    src = """
    VAR a, b, c, d, e, f : BOOL; END_VAR
    a := TRUE OR TRUE AND FALSE;
    b := TRUE XOR TRUE AND FALSE;
    c := TRUE OR TRUE XOR TRUE;
    d := 1 < 2 AND 3 < 4;
    e := 1 < 2 = TRUE;
    f := TRUE & FALSE OR TRUE;
    """
    t = st.tags(src, *"abcdef")
    assert t["a"] is True  # TRUE OR (TRUE AND FALSE); (TRUE OR TRUE) AND FALSE would be FALSE
    assert t["b"] is True  # TRUE XOR (FALSE); (TRUE XOR TRUE) AND FALSE would be FALSE
    assert t["c"] is True  # TRUE OR (TRUE XOR TRUE = FALSE); (TRUE OR TRUE) XOR TRUE would be FALSE
    assert t["d"] is True  # comparisons bind tighter than AND
    assert t["e"] is True  # < before =: (1 < 2) = TRUE
    assert t["f"] is True  # & is AND: (TRUE & FALSE) OR TRUE


def test_bitwise_on_integers(st) -> None:
    src = """
    VAR a, o, x, n, amp : DINT; b : BOOL; s : SINT := 16#0F; ns : SINT; END_VAR
    a := 12 AND 10;
    o := 12 OR 10;
    x := 12 XOR 10;
    n := NOT 0;
    amp := 16#F0 & 16#3C;
    ns := NOT s;
    b := NOT FALSE;
    """
    t = st.tags(src, "a", "o", "x", "n", "amp", "ns", "b")
    assert t["a"] == 8  # 1100 AND 1010 = 1000
    assert t["o"] == 14  # 1100 OR 1010 = 1110
    assert t["x"] == 6  # 1100 XOR 1010 = 0110
    assert t["n"] == -1  # all 32 bits set
    assert t["amp"] == 0x30  # 1111_0000 AND 0011_1100 = 0011_0000 = 48
    assert t["ns"] == -16  # SINT NOT 0000_1111 = 1111_0000 = -16
    assert t["b"] is True


def test_power_integer_and_real(st) -> None:
    src = """
    VAR i, j : DINT; r : REAL; l : LREAL; e : DINT := 3; END_VAR
    i := 2 ** 10;
    j := e ** 0;
    r := 1.5 ** 2.0;
    l := 10.0 ** 2;
    """
    t = st.tags(src, "i", "j", "r", "l")
    assert t["i"] == 1024
    assert t["j"] == 1  # x ** 0 = 1
    assert t["r"] == 2.25
    assert t["l"] == 100.0


def test_radix_literals(st) -> None:
    src = """
    VAR h, b, o, neg, big : DINT; hl : LINT; END_VAR
    h := 16#FF_FF;
    b := 2#1010_1010;
    o := 8#17;
    neg := 16#FFFF_FFFF;
    big := 16#7FFF_FFFF;
    hl := 16#1_0000_0000;
    """
    t = st.tags(src, "h", "b", "o", "neg", "big", "hl")
    assert t["h"] == 65535  # 0xFFFF
    assert t["b"] == 170  # 128 + 32 + 8 + 2
    assert t["o"] == 15  # 1*8 + 7
    assert t["neg"] == -1  # bit pattern 0xFFFFFFFF in a DINT
    assert t["big"] == 2147483647
    assert t["hl"] == 4294967296  # 2^32 needs a LINT


def test_suffixes_and_real_literals(st) -> None:
    src = """
    VAR u : UDINT; l : LINT; ul : ULINT; e, f, g : REAL; n : DINT; END_VAR
    u := 4294967295U;
    l := 5_000_000_000L;
    ul := 18446744073709551615UL;
    e := 1.5e3;
    f := 2.5E-1;
    g := 1_000.25;
    n := 1_000;
    """
    t = st.tags(src, "u", "l", "ul", "e", "f", "g", "n")
    assert t["u"] == 4294967295  # 2^32 - 1
    assert t["l"] == 5000000000
    assert t["ul"] == 2**64 - 1
    assert t["e"] == 1500.0  # 1.5 * 10^3
    assert t["f"] == 0.25
    assert t["g"] == 1000.25  # exact in float32 (1000.25 = 4001/4)
    assert t["n"] == 1000


def test_reals_with_the_point_first_or_last(st) -> None:
    # Studio 5000 accepts `.5` and `5.` (seen in real exports, issue 9); member access,
    # bit access `d.5`, `d.[i]` and CASE ranges `1..5` must keep their meaning around them.
    src = """
    VAR a, b, c, e, f, g, h, y, z : REAL; d, i, k, m : DINT; bit, ib : BOOL; END_VAR
    d := 16#20; i := 5; y := 10.0;
    a [:=] .5;
    b := 5.;
    c := y*.6;
    e := .5e3;
    f := -.25;
    g := -5. + .75;
    h := (2.)*(.5);
    bit := d.5;
    ib := d.[i];
    k := 3;
    CASE k OF 1..5: m := 1; ELSE m := 2; END_CASE;
    CASE k OF -.5..-.25: z := 1.; ELSE z := .125; END_CASE;
    """
    t = st.tags(src, "a", "b", "c", "e", "f", "g", "h", "bit", "ib", "m", "z")
    assert t["a"] == 0.5
    assert t["b"] == 5.0
    assert abs(t["c"] - 6.0) < 1e-5  # 10 * 0.6 in float32
    assert t["e"] == 500.0  # 0.5 * 10^3
    assert t["f"] == -0.25
    assert t["g"] == -4.25  # -5 + 0.75
    assert t["h"] == 1.0  # 2 * 0.5
    assert t["bit"] is True  # 16#20 = bit 5 set
    assert t["ib"] is True  # d.[5], the same bit
    assert t["m"] == 1  # 3 lies in 1..5
    assert t["z"] == 0.125  # DINT 3 matches no label of the REAL range: ELSE


def test_iec_header_words_are_names_in_logix_code(st) -> None:
    # Logix does not reserve PROGRAM, ARRAY, TYPE or STRUCT: real exports call GSV with the
    # class `Program` and name tags `array` (decision 0046); in our header they stay keywords.
    src = """
    TYPE Pair : STRUCT a, b : DINT; END_STRUCT END_TYPE
    VAR array : ARRAY[0..2] OF DINT; type : Pair; struct : DINT; END_VAR
    type.a := 4; type.b := 5;
    array[1] := type.a * type.b;
    struct := array[1] + 1;
    """
    t = st.tags(src, "array[1]", "struct")
    assert t["array[1]"] == 20  # 4 * 5
    assert t["struct"] == 21


def test_bool_literals(st) -> None:
    src = """
    VAR a, b, c, d : BOOL := TRUE; END_VAR
    b := FALSE;
    c := 0;
    d := 1;
    """
    t = st.tags(src, "a", "b", "c", "d")
    assert t == {"a": True, "b": False, "c": False, "d": True}


def test_string_escapes(st) -> None:
    src = """
    VAR s, q, h : STRING; END_VAR
    s := 'It$'s $$5$N$T$41';
    q := 'a$Lb$rc$pd';
    h := '$0D$0a';
    """
    t = st.tags(src, "s", "s.LEN", "q", "h")
    # $' -> ', $$ -> $, $N -> LF, $T -> TAB, $41 -> 'A'
    assert t["s"] == "It's $5\n\tA"
    assert t["s.LEN"] == 10  # I t ' s space $ 5 LF TAB A
    assert t["q"] == "a\nb\rc\fd"  # $L line feed, $r return, $p form feed (case-insensitive)
    assert t["h"] == "\r\n"  # hex bytes 0D 0A


def test_comment_forms(st) -> None:
    src = """
    VAR a, b, c, d : DINT; s : STRING; END_VAR
    // a := 100;
    a := 1; // trailing comment
    (* b := 100;
       still commented: END_IF ;;
    *)
    b := 2 (* inline *) + 3;
    /* c := 100;
       d := 100; */
    c := /* inside */ 4;
    d := 5; (* one *) (* two *) /* three */ // four
    s := 'x // y (* z *) /* w */';
    """
    t = st.tags(src, "a", "b", "c", "d", "s")
    assert t["a"] == 1
    assert t["b"] == 5  # 2 + 3; the inline comment is whitespace
    assert t["c"] == 4
    assert t["d"] == 5
    assert t["s"] == "x // y (* z *) /* w */"  # markers inside a string are text


def test_case_insensitive_keywords_and_names(st) -> None:
    src = """
    var Counter : dint; end_var
    if counter = 0 then COUNTER := counter + 1; end_if;
    """
    assert st.tags(src, "COUNTER")["COUNTER"] == 1
