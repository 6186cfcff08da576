"""The catalog holds every instruction of the Logix reference manuals.

The lists below are our own index of the manuals' chapters (1756-RM003 general
instructions, 1756-RM006 process control and drives, the equipment phase and equipment
sequence instructions, the GuardLogix safety application instructions, and the
instructions Studio 5000 added up to v37). Each name must be a catalog instruction or
alias in some language. Motion instructions are indexed by the motion catalog's own tests.
"""

from __future__ import annotations

import pytest

from stdlib import catalog

RM003 = {
    "bit": "XIC XIO OTE OTL OTU ONS OSR OSF OSRI OSFI",
    "timer and counter": "TON TOF RTO TONR TOFR RTOR CTU CTD CTUD RES",
    "input/output": "MSG GSV SSV IOT",
    "compare": "CMP EQU EQ NEQ NE GRT GT GEQ GE LES LT LEQ LE LIM LIMIT MEQ IsINF IsNAN",
    "compute/math": "CPT ADD SUB MUL DIV MOD SQR SQRT NEG ABS",
    "move/logical": "MOV MOVE MVM MVMT BTD BTDT CLR SWPB AND OR XOR NOT "
    "BAND BOR BXOR BNOT DFF JKFF RESD SETD",
    "array (file)/misc": "FAL FSC COP CPS FLL AVE SRT STD SIZE",
    "array (file)/shift": "BSL BSR FFL FFU LFL LFU",
    "sequencer": "SQI SQO SQL",
    "program control": "JMP LBL JSR RET SBR JXR TND MCR UID UIE AFI NOP EOT SFP SFR EVENT",
    "for/break": "FOR BRK",
    "special": "FBC DDT DTR PID",
    "trigonometric": "SIN COS TAN ASN ASIN ACS ACOS ATN ATAN ATAN2",
    "advanced math": "LN LOG XPY EXPT",
    "math conversion": "DEG RAD TOD TO_BCD FRD BCD_TO TRN TRUNC",
    "ASCII serial port": "ABL ACB ACL AHL ARD ARL AWA AWT",
    "ASCII string": "CONCAT DELETE FIND INSERT MID",
    "ASCII conversion": "DTOS STOD RTOS STOR UPPER LOWER",
    "alarm": "ALMD ALMA",
    "license": "LV",
    "program conversion": "PCE",
}

RM006 = {
    "process control": "ALM D2SD D3SD DEDT FGEN LDLG PIDE POSP RMPS SCL SRTP TOT IMC CC MMC HMIBC",
    "drives": "INTG PI PMUL SCRV SOC UPDN",
    "filters": "DERV HPF LDL2 LPF NTCH",
    "select/limit": "ESEL HLL MUX RLIM SEL SNEG SSUM",
    "statistical": "MAVE MAXC MINC MSTD",
}

BATCH = {
    "equipment phase": "PSC PCMD POVR PFL PCLF PXRQ PPD PRNP PATT PDET",
    "equipment sequence": "SATT SCLF SCMD SDET SOVR SASI",
}

SAFETY = {
    "safety application": "ESTOP RIN DIN ENPEN LC ROUT DCS DCST DCSTL DCSTM DCSRT DCM SMAT "
    "THRS THRSE CROUT FPMS EPMS TSAM TSSM FSBM AVC MVC MMVC CBCM CBIM CBSSM CPM CSM",
}

# Instructions other helpers of issue 9 add in parallel (process/communication and ASCII,
# the ladder PID, FOR/BRK/EVENT, the alarm instructions): indexed above, checked once merged.
# Remove a name from this set when its entry lands.
OTHER_HELPERS = set("MSG PID SCL ALMD ALMA FOR BRK EVENT ABL ACB ACL AHL ARD ARL AWA AWT".split())

CHAPTERS = [
    (f"{book} {chapter}", name)
    for book, chapters in (("RM003", RM003), ("RM006", RM006), ("batch", BATCH), ("safety", SAFETY))
    for chapter, names in chapters.items()
    for name in names.split()
    if name not in OTHER_HELPERS
]


@pytest.mark.parametrize(("chapter", "name"), CHAPTERS, ids=[f"{c}:{n}" for c, n in CHAPTERS])
def test_manual_instruction_is_in_the_catalog(chapter: str, name: str) -> None:
    assert catalog().instruction_any(name) is not None, f"{chapter}: {name} missing"


def test_index_has_no_duplicates_across_chapters() -> None:
    names = [n for _, n in CHAPTERS]
    assert len(names) == len(set(names))


def test_predefined_types_of_these_instructions_are_known() -> None:
    cat = catalog()
    for name in (
        "PID_ENHANCED PIDE_AUTOTUNE ALARM DISCRETE_2STATE DISCRETE_3STATE DEADTIME "
        "FUNCTION_GENERATOR LEAD_LAG POSITION_PROP RAMP_SOAK SPLIT_RANGE TOTALIZER IMC CC MMC "
        "HMIBC INTEGRATOR PROP_INT PULSE_MULTIPLIER S_CURVE SEC_ORDER_CONTROLLER UP_DOWN_ACCUM "
        "DERIVATIVE FILTER_HIGH_PASS FILTER_LOW_PASS FILTER_NOTCH LEAD_LAG_SEC_ORDER "
        "SELECT_ENHANCED HL_LIMIT MULTIPLEXER RATE_LIMITER SELECT SELECTABLE_NEGATE "
        "SELECTED_SUMMER MOVING_AVERAGE MOVING_STD_DEV MAXIMUM_CAPTURE MINIMUM_CAPTURE "
        "FBD_BOOLEAN_AND FBD_BOOLEAN_OR FBD_BOOLEAN_XOR FBD_BOOLEAN_NOT FLIP_FLOP_D FLIP_FLOP_JK "
        "DOMINANT_RESET DOMINANT_SET FBD_MASKED_MOVE FBD_BIT_FIELD_DISTRIBUTE FBD_MATH "
        "FBD_MATH_ADVANCED FBD_COMPARE FBD_LIMIT FBD_MASK_EQUAL FBD_LOGICAL FBD_CONVERT "
        "FBD_TRUNCATE PHASE PHASE_INSTRUCTION SEQUENCE SEQUENCE_INSTRUCTION SFC_STEP SFC_ACTION "
        "SFC_STOP EXT_ROUTINE_CONTROL ALARM_SET_CONTROL MODULE CONNECTION_STATUS EMERGENCY_STOP DCI_STOP "
        "MUTING_TWO_SENSOR_ASYM CB_CONTINUOUS_MODE MANUAL_VALVE_CONTROL"
    ).split():
        assert cat.type(name) is not None, name


def test_a_program_using_these_instructions_has_no_unknown_instruction(st) -> None:  # noqa: ANN001
    """Process, drives, phase and SFC calls are known (U304 at most), none is E103."""
    src = """
    VAR
      loop : PID_ENHANCED; ramp : RAMP_SOAK; rv, sv, stime : REAL[4]; dt : DEADTIME;
      store : REAL[10]; sc : S_CURVE; lim : HL_LIMIT; ff : FLIP_FLOP_D; tot : TOTALIZER;
      ph : PHASE; result : DINT; r : REAL; b : BOOL; x : REAL[4]; y : REAL[4]; gen : FUNCTION_GENERATOR;
    END_VAR
    PIDE(loop);
    RMPS(ramp, rv, sv, stime);
    DEDT(dt, store);
    FGEN(gen, x, y, x, y);
    SCRV(sc);
    HLL(lim);
    DFF(ff);
    TOT(tot);
    PCMD(ph, Start, result);
    POVR(ph, Abort, 0);
    PSC();
    UID(); UIE();
    b := IsNAN(r) OR IsINF(r);
    r := ATAN2(r, 1.0);
    """
    r = st.check(src)
    codes = {d["code"] for d in r.json}
    assert "E103" not in codes and codes <= {"U304"}, r.json
