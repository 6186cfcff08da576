"""Source-protected AOIs (decision 0057): declared from the parameters an export shows in
clear, reported once (U302) where defined, and called like any AOI.

The fixture follows how Studio exports a protected AOI (as in the SD168700 and
Master_Main_Program exports of the corpus): `<EncodedData EncodedType=
"AddOnInstructionDefinition">` with `<Parameters>` in clear and the local tags and routines
inside the encrypted text.
"""

from __future__ import annotations

from pathlib import Path

from interpreter.runtime.loader import load
from interpreter.semantics.types import StructType

EXPORT = """<?xml version="1.0" encoding="UTF-8" standalone="yes"?>
<RSLogix5000Content SchemaRevision="1.0" SoftwareRevision="32.02" TargetName="Prot" TargetType="Controller">
<Controller Use="Target" Name="Prot" ProcessorType="1756-L83E" MajorRev="32" MinorRev="11">
<AddOnInstructionDefinitions>
<EncodedData EncodedType="AddOnInstructionDefinition" Name="Valve" Revision="1.0" Vendor="Someone" EncryptionConfig="9">
<Description><![CDATA[valve control]]></Description>
<Parameters>
<Parameter Name="EnableIn" TagType="Base" DataType="BOOL" Usage="Input" Radix="Decimal" Required="false" Visible="false"/>
<Parameter Name="EnableOut" TagType="Base" DataType="BOOL" Usage="Output" Radix="Decimal" Required="false" Visible="false"/>
<Parameter Name="Setpoint" TagType="Base" DataType="REAL" Usage="Input" Radix="Float" Required="true" Visible="true"/>
<Parameter Name="Count" TagType="Base" DataType="DINT" Usage="Output" Radix="Decimal" Required="true" Visible="true"/>
<Parameter Name="Buffer" TagType="Base" DataType="DINT" Dimensions="4" Usage="InOut" Required="true" Visible="true"/>
<Parameter Name="Open" TagType="Base" DataType="BOOL" Usage="Output" Radix="Decimal" Required="false" Visible="true"/>
<Parameter Name="Sts_EN" TagType="Alias" Usage="Output" Radix="Decimal" AliasFor="_bSts.0" Required="false" Visible="true"/>
</Parameters>
QUJDREVGR0hJSktMTU5PUFFSU1RVVldYWVo=
</EncodedData>
</AddOnInstructionDefinitions>
<Tags>
<Tag Name="V1" TagType="Base" DataType="Valve"/>
<Tag Name="sp" TagType="Base" DataType="REAL"/>
<Tag Name="n" TagType="Base" DataType="DINT"/>
<Tag Name="buf" TagType="Base" DataType="{buffer}" Dimensions="4"/>
<Tag Name="b" TagType="Base" DataType="BOOL"/>
</Tags>
<Programs>
<Program Name="Main" MainRoutineName="Rungs">
<Routines>
<Routine Name="Rungs" Type="RLL"><RLLContent>
<Rung Number="0" Type="N"><Text><![CDATA[XIC(b)Valve(V1,sp,n,buf)XIC(V1.Open)OTE(b);]]></Text></Rung>
</RLLContent></Routine>
<Routine Name="Text" Type="ST"><STContent>
<Line Number="0"><![CDATA[Valve(V1, 12.5, n, buf); b := V1.Open AND V1.Count > 2 AND V1.Sts_EN;]]></Line>
</STContent></Routine>
</Routines>
</Program>
</Programs>
</Controller>
</RSLogix5000Content>
"""


def check(tmp_path: Path, buffer: str = "DINT") -> list[tuple[str, int]]:
    path = tmp_path / "prot.L5X"
    path.write_text(EXPORT.format(buffer=buffer))
    loaded = load([path])
    st = loaded.model.types.get("VALVE")
    assert isinstance(st, StructType)
    # the instance holds the parameters shown in clear (locals are encrypted); an alias
    # parameter for a bit of an encrypted local is a BOOL of its own
    assert [(m, str(t)) for m, t in st.members][:6] == [
        ("EnableIn", "BOOL"),
        ("EnableOut", "BOOL"),
        ("Setpoint", "REAL"),
        ("Count", "DINT"),
        ("Open", "BOOL"),
        ("Sts_EN", "BOOL"),
    ]
    return [(d.code, d.span.line) for d in loaded.diagnostics]


def test_protected_aoi_is_reported_once_and_called_with_its_parameters(tmp_path: Path) -> None:
    # one U302 at the definition; the calls, the instance tag and its members check clean
    assert check(tmp_path) == [("U302", 5)]


def test_protected_aoi_arguments_are_checked(tmp_path: Path) -> None:
    # the InOut Buffer is a DINT[4]: a REAL[4] is the wrong type, in both calls
    assert check(tmp_path, buffer="REAL") == [("U302", 5), ("E105", 30), ("E105", 33)]


def test_an_inout_array_parameter_needs_an_array(tmp_path: Path) -> None:
    # n is a DINT: the element type fits, the shape does not; one E105, not two
    path = tmp_path / "shape.L5X"
    path.write_text(EXPORT.format(buffer="DINT").replace("Valve(V1,sp,n,buf)", "Valve(V1,sp,n,n)"))
    found = [(d.code, d.message) for d in load([path]).diagnostics]
    assert found == [
        (
            "U302",
            "add-on instruction 'Valve' is protected (encoded): calls are checked against its"
            " parameters, and its logic does not run",
        ),
        (
            "E105",
            "Valve InOut parameter Buffer needs a DINT[4], not DINT (program Main, routine"
            " Rungs, rung 0)",
        ),
    ]
