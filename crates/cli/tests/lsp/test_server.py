"""`urdf_validate server` end to end, through pytest-lsp's client: diagnostics (ranges, files, related
information, code links), hover, definition, references, symbols, completion, code actions applied and
re-validated, a newer edit cancelling the analysis under way, half-typed XML, shutdown."""

import asyncio

from lsprotocol import types

from conftest import (
    change,
    codes,
    copy_pr2,
    open_file,
    position_of,
    wait_for,
)

BROKEN_AXIS = """<?xml version="1.0"?>
<robot name="arm">
  <link name="base">
    <inertial><mass value="5"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <joint name="shoulder" type="revolute">
    <parent link="base"/>
    <child link="upper"/>
    <axis xyz="0 0 2"/>
    <limit lower="-1" upper="1" effort="100" velocity="1"/>
  </joint>
  <link name="upper">
    <inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
</robot>
"""


def apply_edits(text: str, edits: list[types.TextEdit]) -> str:
    """`edits` applied to ASCII `text` (from the last to the first)."""
    lines = text.split("\n")
    starts = [0]
    for line in lines[:-1]:
        starts.append(starts[-1] + len(line) + 1)
    offset = lambda p: starts[p.line] + p.character  # noqa: E731
    for edit in sorted(edits, key=lambda e: offset(e.range.start), reverse=True):
        text = text[: offset(edit.range.start)] + edit.new_text + text[offset(edit.range.end) :]
    return text


async def test_pr2_diagnostics_hover_and_navigation(client, tmp_path):
    pr2 = copy_pr2(tmp_path)
    text = pr2.read_text()
    uri = open_file(client, pr2)
    # Structural findings first, then the physics ones (U701: joints too weak) once statics has run.
    await wait_for("PR2's structural diagnostics", lambda: "U402" in codes(client, uri))
    await wait_for("PR2's physics diagnostics", lambda: "U701" in codes(client, uri), timeout=120)
    first = client.published[0]
    assert first.uri == uri and "U701" not in [d.code for d in first.diagnostics], (
        "the structural pass is published before physics"
    )
    undersized = [d for d in client.diagnostics[uri] if d.code == "U701"]
    for diagnostic in undersized:
        assert diagnostic.severity == types.DiagnosticSeverity.Error
        assert diagnostic.source == "urdf_validate"
        assert diagnostic.code_description.href.endswith("/rules/u701.html")
        line = text.split("\n")[diagnostic.range.start.line]
        flagged = line[diagnostic.range.start.character : diagnostic.range.end.character]
        assert flagged, f"an empty range on {line!r}"
        assert "effort" in line or "<joint" in line or "<limit" in line, line

    # Hover on a joint: its statics at the analysed pose.
    weak = undersized[0].message.split("'")[1]
    hover = await client.text_document_hover_async(
        types.HoverParams(
            text_document=types.TextDocumentIdentifier(uri=uri),
            position=position_of(text, f'<joint name="{weak}"', len('<joint name="') + 1),
        )
    )
    assert hover is not None, "no hover on the weak joint"
    assert "gravity torque" in hover.contents.value and "effort_needed" in hover.contents.value
    assert "margin" in hover.contents.value

    # Hover on a link: mass properties.
    hover = await client.text_document_hover_async(
        types.HoverParams(
            text_document=types.TextDocumentIdentifier(uri=uri),
            position=position_of(text, '<link name="base_link"', len('<link name="') + 2),
        )
    )
    assert "mass:" in hover.contents.value and "principal moments" in hover.contents.value
    assert "mass carried" in hover.contents.value

    # Hover on a mesh path: the file it resolves to.
    mesh = text.index('<mesh filename="package://') + len('<mesh filename="') + 3
    line = text.count("\n", 0, mesh)
    hover = await client.text_document_hover_async(
        types.HoverParams(
            text_document=types.TextDocumentIdentifier(uri=uri),
            position=types.Position(line=line, character=mesh - text.rfind("\n", 0, mesh) - 1),
        )
    )
    assert "→" in hover.contents.value and "pr2_description" in hover.contents.value

    # Definition of the parent link of a joint, and every reference to it.
    use = position_of(text, '<parent link="base_link"', len('<parent link="') + 1)
    definition = await client.text_document_definition_async(
        types.DefinitionParams(text_document=types.TextDocumentIdentifier(uri=uri), position=use)
    )
    assert len(definition) == 1
    assert definition[0].range.start == position_of(text, '<link name="base_link"', len('<link name="'))
    references = await client.text_document_references_async(
        types.ReferenceParams(
            text_document=types.TextDocumentIdentifier(uri=uri),
            position=use,
            context=types.ReferenceContext(include_declaration=True),
        )
    )
    expected = text.count('link="base_link"') + text.count('<link name="base_link"') + text.count(
        'reference="base_link"'
    )
    assert len(references) == expected

    # A material used in a visual: its definition at the robot's top level, its colour on hover.
    grey_use = text.index('<material name="Grey"', text.index('<material name="Grey"') + 1) + len('<material name="') + 1
    grey = types.Position(
        line=text.count("\n", 0, grey_use), character=grey_use - text.rfind("\n", 0, grey_use) - 1
    )
    definition = await client.text_document_definition_async(
        types.DefinitionParams(text_document=types.TextDocumentIdentifier(uri=uri), position=grey)
    )
    assert [d.range.start for d in definition] == [position_of(text, '<material name="Grey"', len('<material name="'))]
    hover = await client.text_document_hover_async(
        types.HoverParams(text_document=types.TextDocumentIdentifier(uri=uri), position=grey)
    )
    assert "**material `Grey`**" in hover.contents.value and "colour rgba" in hover.contents.value

    # Symbols: the kinematic tree, base_footprint at the root.
    symbols = await client.text_document_document_symbol_async(
        types.DocumentSymbolParams(text_document=types.TextDocumentIdentifier(uri=uri))
    )
    assert symbols[0].name == "base_footprint" and symbols[0].children


async def test_fix_is_applied_and_revalidated(client, tmp_path):
    robot = tmp_path / "arm.urdf"
    robot.write_text(BROKEN_AXIS)
    uri = open_file(client, robot)
    await wait_for("U310", lambda: "U310" in codes(client, uri))
    [axis] = [d for d in client.diagnostics[uri] if d.code == "U310"]
    flagged = BROKEN_AXIS.split("\n")[axis.range.start.line][
        axis.range.start.character : axis.range.end.character
    ]
    assert flagged == "0 0 2"
    actions = await client.text_document_code_action_async(
        types.CodeActionParams(
            text_document=types.TextDocumentIdentifier(uri=uri),
            range=axis.range,
            context=types.CodeActionContext(diagnostics=[axis]),
        )
    )
    titles = [a.title for a in actions]
    fix = next(a for a in actions if a.title.startswith("Fix U310"))
    assert fix.kind == types.CodeActionKind.QuickFix and fix.is_preferred
    assert any(t.startswith("Suppress U310") for t in titles), titles
    assert any(a.kind == types.CodeActionKind.SourceFixAll for a in actions), titles
    fixed = apply_edits(BROKEN_AXIS, fix.edit.changes[uri])
    assert '<axis xyz="0 0 1"/>' in fixed
    change(client, uri, 2, fixed)
    await wait_for("U310 gone after the fix", lambda: "U310" not in codes(client, uri) and any(
        p.version == 2 for p in client.published if p.uri == uri
    ))

    # "Suppress this finding" inserts a comment that silences it.
    suppress = next(a for a in actions if a.title.startswith("Suppress U310"))
    suppressed = apply_edits(BROKEN_AXIS, suppress.edit.changes[uri])
    assert "<!-- urdf-validate: ignore U310 -->" in suppressed
    change(client, uri, 3, suppressed)
    await wait_for("U310 suppressed", lambda: any(
        p.version == 3 for p in client.published if p.uri == uri
    ))
    assert "U310" not in codes(client, uri)


async def test_unsafe_fixes_are_marked_and_left_out_of_fix_all(client, tmp_path):
    robot = tmp_path / "arm.urdf"
    # The upper link's mass 0.5 m out along x on a y axis: about 4.9 N·m to hold, 0.01 declared.
    text = BROKEN_AXIS.replace('effort="100"', 'effort="0.01"').replace(
        'xyz="0 0 2"', 'xyz="0 2 0"'
    ).replace('<inertial><mass value="1"/>', '<inertial><origin xyz="0.5 0 0"/><mass value="1"/>')
    robot.write_text(text)
    uri = open_file(client, robot)
    await wait_for("U701", lambda: "U701" in codes(client, uri), timeout=120)
    [weak] = [d for d in client.diagnostics[uri] if d.code == "U701"]
    actions = await client.text_document_code_action_async(
        types.CodeActionParams(
            text_document=types.TextDocumentIdentifier(uri=uri),
            range=types.Range(start=types.Position(line=0, character=0), end=types.Position(line=99, character=0)),
            context=types.CodeActionContext(diagnostics=[weak]),
        )
    )
    unsafe = [a for a in actions if a.title.startswith("Fix U701")]
    assert unsafe and "unsafe" in unsafe[0].title and not unsafe[0].is_preferred
    [fix_all] = [a for a in actions if a.kind == types.CodeActionKind.SourceFixAll]
    after = apply_edits(text, fix_all.edit.changes[uri])
    assert 'effort="0.01"' in after, "fix all left the unsafe effort fix out"
    assert '<axis xyz="0 1 0"/>' in after


XACRO_ROOT = """<?xml version="1.0"?>
<robot name="tree" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="parts.xacro"/>
  <link name="base">
    <inertial><mass value="5"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <xacro:arm prefix="left" parent="base"/>
</robot>
"""

XACRO_PARTS = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="arm" params="prefix parent">
    <joint name="${prefix}_joint" type="revolute">
      <parent link="${parent}"/>
      <child link="${prefix}_link"/>
      <axis xyz="0 0 2"/>
      <limit lower="-1" upper="1" effort="100" velocity="1"/>
    </joint>
    <link name="${prefix}_link">
      <inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
    </link>
  </xacro:macro>
</robot>
"""


async def test_xacro_findings_are_published_on_the_included_file(client, tmp_path):
    (tmp_path / "parts.xacro").write_text(XACRO_PARTS)
    root = tmp_path / "robot.urdf.xacro"
    root.write_text(XACRO_ROOT)
    parts_uri = (tmp_path / "parts.xacro").as_uri()
    uri = open_file(client, root)
    await wait_for("U310 on parts.xacro", lambda: "U310" in codes(client, parts_uri))
    [axis] = [d for d in client.diagnostics[parts_uri] if d.code == "U310"]
    line = XACRO_PARTS.split("\n")[axis.range.start.line]
    assert line[axis.range.start.character : axis.range.end.character] == "0 0 2"
    [call] = axis.related_information
    assert call.location.uri == uri and "in macro 'arm'" in call.message
    assert call.location.range.start == position_of(XACRO_ROOT, "<xacro:arm", 0)
    assert "U310" not in codes(client, uri)

    # The fix edits the included file (its literal), from either document.
    actions = await client.text_document_code_action_async(
        types.CodeActionParams(
            text_document=types.TextDocumentIdentifier(uri=parts_uri),
            range=axis.range,
            context=types.CodeActionContext(diagnostics=[axis]),
        )
    )
    fix = next(a for a in actions if a.title.startswith("Fix U310"))
    assert apply_edits(XACRO_PARTS, fix.edit.changes[parts_uri]).count('xyz="0 0 1"') == 1

    # Saving the include re-validates the robot that reads it.
    (tmp_path / "parts.xacro").write_text(apply_edits(XACRO_PARTS, fix.edit.changes[parts_uri]))
    open_file(client, tmp_path / "parts.xacro")
    client.text_document_did_save(
        types.DidSaveTextDocumentParams(text_document=types.TextDocumentIdentifier(uri=parts_uri))
    )
    await wait_for("U310 gone after saving the include", lambda: "U310" not in codes(client, parts_uri))


async def test_a_fix_is_offered_anywhere_on_its_line_and_once_for_a_macro(client, tmp_path):
    # The arm macro called twice: its literal `0 0 2` is flagged for each arm, and fixed by one edit.
    (tmp_path / "parts.xacro").write_text(XACRO_PARTS)
    root = tmp_path / "robot.urdf.xacro"
    root.write_text(XACRO_ROOT.replace(
        '<xacro:arm prefix="left" parent="base"/>',
        '<xacro:arm prefix="left" parent="base"/>\n  <xacro:arm prefix="right" parent="base"/>',
    ))
    parts_uri = (tmp_path / "parts.xacro").as_uri()
    open_file(client, root)
    await wait_for("U310 on parts.xacro", lambda: "U310" in codes(client, parts_uri))
    axis = next(d for d in client.diagnostics[parts_uri] if d.code == "U310")
    # The cursor at the start of the flagged line, nowhere near `0 0 2`: the fix is still offered.
    start_of_line = types.Position(line=axis.range.start.line, character=0)
    actions = await client.text_document_code_action_async(
        types.CodeActionParams(
            text_document=types.TextDocumentIdentifier(uri=parts_uri),
            range=types.Range(start=start_of_line, end=start_of_line),
            context=types.CodeActionContext(diagnostics=[]),
        )
    )
    titles = [a.title for a in actions]
    fixes = [a for a in actions if a.title.startswith("Fix U310")]
    assert len(fixes) == 1, f"one fix, not one per macro call: {titles}"
    assert len([t for t in titles if t.startswith("Suppress U310")]) <= 1, titles
    assert apply_edits(XACRO_PARTS, fixes[0].edit.changes[parts_uri]).count('xyz="0 0 1"') == 1
    # A line without a finding offers no quick fix.
    elsewhere = types.Position(line=0, character=0)
    actions = await client.text_document_code_action_async(
        types.CodeActionParams(
            text_document=types.TextDocumentIdentifier(uri=parts_uri),
            range=types.Range(start=elsewhere, end=elsewhere),
            context=types.CodeActionContext(diagnostics=[]),
        )
    )
    assert not [a for a in actions if a.kind == types.CodeActionKind.QuickFix], [a.title for a in actions]


async def test_xacro_macros_and_properties_navigate_across_includes(client, tmp_path):
    (tmp_path / "parts.xacro").write_text(XACRO_PARTS)
    root = tmp_path / "robot.urdf.xacro"
    root.write_text(XACRO_ROOT)
    parts_uri = (tmp_path / "parts.xacro").as_uri()
    uri = open_file(client, root)
    # The robot's files (its includes) are known once its analysis has read them.
    await wait_for("the tree's diagnostics", lambda: "U310" in codes(client, parts_uri))
    call = position_of(XACRO_ROOT, "<xacro:arm", len("<xacro:") + 1)
    root_document = types.TextDocumentIdentifier(uri=uri)

    # A macro call: its definition in the included file, its signature on hover.
    definition = await client.text_document_definition_async(
        types.DefinitionParams(text_document=root_document, position=call)
    )
    assert [(d.uri, d.range.start) for d in definition] == [
        (parts_uri, position_of(XACRO_PARTS, 'name="arm"', len('name="')))
    ]
    hover = await client.text_document_hover_async(types.HoverParams(text_document=root_document, position=call))
    assert "**xacro macro `arm`**(prefix parent)" in hover.contents.value
    assert "defined at parts.xacro:3" in hover.contents.value

    # A macro parameter: defined by the params, used as ${prefix} three times.
    open_file(client, tmp_path / "parts.xacro")
    parts_document = types.TextDocumentIdentifier(uri=parts_uri)
    use = position_of(XACRO_PARTS, "${prefix}_joint", 3)
    references = await client.text_document_references_async(
        types.ReferenceParams(
            text_document=parts_document,
            position=use,
            context=types.ReferenceContext(include_declaration=True),
        )
    )
    assert len(references) == 1 + XACRO_PARTS.count("${prefix}")
    hover = await client.text_document_hover_async(types.HoverParams(text_document=parts_document, position=use))
    assert "**parameter `prefix`** of xacro macro `arm`" in hover.contents.value

    # Completion of a macro name after <xacro: and of a property in ${.
    completion = await client.text_document_completion_async(
        types.CompletionParams(text_document=root_document, position=position_of(XACRO_ROOT, "<xacro:arm", len("<xacro:a")))
    )
    items = completion.items if hasattr(completion, "items") else completion
    assert "arm" in [i.label for i in items]
    completion = await client.text_document_completion_async(
        types.CompletionParams(text_document=parts_document, position=position_of(XACRO_PARTS, "${parent}", 3))
    )
    items = completion.items if hasattr(completion, "items") else completion
    assert {"parent", "prefix"} <= {i.label for i in items}


async def test_a_newer_edit_cancels_the_analysis_under_way(client, tmp_path):
    pr2 = copy_pr2(tmp_path)
    text = pr2.read_text()
    uri = open_file(client, pr2)
    await wait_for("PR2 analysed", lambda: "U701" in codes(client, uri), timeout=120)
    # Version 2 makes a joint far too weak and raises the torso (so its physics pass samples both arms
    # again, after the typing pause; an effort edit alone would take them from the memo and publish at
    # once); as soon as its structural pass is out, version 3 takes it back. Version 2's physics (U701
    # on that joint) must never be published.
    joint = "r_elbow_flex_joint"
    at = text.index('effort="30"', text.index(f'<joint name="{joint}"'))
    assert not [d for d in client.diagnostics[uri] if d.code == "U701" and f"'{joint}'" in d.message]
    weak = text[:at] + 'effort="0.001"' + text[at + len('effort="30"') :]
    torso = weak.index('xyz="-0.05 0 0.739675"', weak.index('<joint name="torso_lift_joint"'))
    weak = weak[:torso] + 'xyz="-0.05 0 0.75"' + weak[torso + len('xyz="-0.05 0 0.739675"') :]
    change(client, uri, 2, weak)
    await wait_for("version 2's structural pass", lambda: any(
        p.uri == uri and p.version == 2 for p in client.published
    ))
    change(client, uri, 3, text)
    # Each version is published twice: structure, then physics.
    await wait_for("version 3's physics", lambda: len([
        p for p in client.published if p.uri == uri and p.version == 3
    ]) >= 2, timeout=120)
    # Time for a stray physics pass of version 2 to arrive, were it not cancelled.
    await asyncio.sleep(1.0)
    version_2 = [p for p in client.published if p.uri == uri and p.version == 2]
    assert not any(
        d.code == "U701" and f"'{joint}'" in d.message for p in version_2 for d in p.diagnostics
    ), "the physics pass of version 2 was published after version 3 arrived"
    # Meanwhile the physics findings of version 1 stayed shown (no flicker while typing).
    assert all(any(d.code == "U701" for d in p.diagnostics) for p in version_2)


SRDF = """<?xml version="1.0"?>
<robot name="arm">
  <group name="arm"><chain base_link="base" tip_link="upper"/><joint name="shoulder"/></group>
  <disable_collisions link1="base" link2="upper" reason="Adjacent"/>
</robot>
"""


async def test_references_reach_the_robots_srdf(client, tmp_path):
    path = tmp_path / "arm.urdf"
    path.write_text(BROKEN_AXIS)
    (tmp_path / "arm.srdf").write_text(SRDF)
    srdf_uri = (tmp_path / "arm.srdf").as_uri()
    uri = open_file(client, path)
    await wait_for("the arm's diagnostics", lambda: "U310" in codes(client, uri))
    references = await client.text_document_references_async(
        types.ReferenceParams(
            text_document=types.TextDocumentIdentifier(uri=uri),
            position=position_of(BROKEN_AXIS, '<link name="base"', len('<link name="') + 1),
            context=types.ReferenceContext(include_declaration=False),
        )
    )
    in_srdf = sorted((r.range.start.line, r.range.start.character) for r in references if r.uri == srdf_uri)
    assert in_srdf == [
        (p.line, p.character)
        for p in (
            position_of(SRDF, 'base_link="base"', len('base_link="')),
            position_of(SRDF, 'link1="base"', len('link1="')),
        )
    ]
    references = await client.text_document_references_async(
        types.ReferenceParams(
            text_document=types.TextDocumentIdentifier(uri=uri),
            position=position_of(BROKEN_AXIS, '<joint name="shoulder"', len('<joint name="') + 1),
            context=types.ReferenceContext(include_declaration=False),
        )
    )
    assert [r.uri for r in references] == [srdf_uri]


def folded_arm() -> str:
    """A four-joint arm folded back onto itself: 'hand' touches 'base', 'l3' touches 'l1' (U601)."""
    inertial = (
        '<inertial><mass value="1"/><inertia ixx="0.00167" iyy="0.00167" izz="0.00167" '
        'ixy="0" ixz="0" iyz="0"/></inertial><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>'
    )
    names = ["base", "l1", "l2", "l3", "hand"]
    lines = ['<?xml version="1.0"?>', '<robot name="folded">', f'  <link name="base">{inertial}</link>']
    for i, z in enumerate(["0.3", "0.3", "-0.3", "-0.3"], start=1):
        lines.append(
            f'  <joint name="j{i}" type="revolute"><parent link="{names[i - 1]}"/><child link="{names[i]}"/>'
            f'<origin xyz="0 0 {z}"/><axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="100" velocity="1"/></joint>'
        )
        lines.append(f'  <link name="{names[i]}">{inertial}</link>')
    return "\n".join(lines + ["</robot>", ""])


async def test_a_pair_finding_relates_both_links(client, tmp_path):
    text = folded_arm()
    path = tmp_path / "folded.urdf"
    path.write_text(text)
    uri = open_file(client, path)
    await wait_for("U601", lambda: "U601" in codes(client, uri), timeout=120)
    [pair] = [d for d in client.diagnostics[uri] if d.code == "U601" and "'hand'" in d.message]
    # The finding is on 'hand' (its line); the other link of the pair is related information.
    assert pair.range.start.line == position_of(text, '<link name="hand"').line
    related = {r.message: r.location.range.start for r in pair.related_information}
    assert related == {"link 'base'": position_of(text, '<link name="base"', len('<link name="'))}


async def test_half_typed_xml_is_a_diagnostic_and_the_last_analysis_stays(client, tmp_path):
    robot = tmp_path / "arm.urdf"
    robot.write_text(BROKEN_AXIS)
    uri = open_file(client, robot)
    await wait_for("U310", lambda: "U310" in codes(client, uri))
    half = BROKEN_AXIS.replace('<child link="upper"/>', '<child link="up')
    change(client, uri, 2, half)
    await wait_for("the XML error", lambda: any(
        "not well-formed" in d.message for d in client.diagnostics.get(uri, [])
    ))
    [error] = [d for d in client.diagnostics[uri] if d.code == "xml-syntax"]
    assert error.severity == types.DiagnosticSeverity.Error
    assert str(tmp_path) not in error.message, "the editor shows the file: no path in the message"
    # roxmltree stops where the attribute value breaks: on the child line or just after it.
    child_line = BROKEN_AXIS.split("\n").index('    <child link="upper"/>')
    assert child_line <= error.range.start.line <= child_line + 1, error
    # The last analysis's findings stay shown, marked stale, instead of all vanishing while typing.
    [stale] = [d for d in client.diagnostics[uri] if d.code == "U310"]
    assert stale.message.endswith("(from the last text that parsed)"), stale
    # Hover still answers from the last good analysis, and the server goes on answering.
    hover = await client.text_document_hover_async(
        types.HoverParams(
            text_document=types.TextDocumentIdentifier(uri=uri),
            position=position_of(half, '<link name="base"', len('<link name="') + 1),
        )
    )
    assert "mass: 5 kg" in hover.contents.value
    completion = await client.text_document_completion_async(
        types.CompletionParams(
            text_document=types.TextDocumentIdentifier(uri=uri),
            position=position_of(half, '<parent link="', len('<parent link="')),
        )
    )
    assert {item.label for item in completion} >= {"base", "upper"}
    change(client, uri, 3, BROKEN_AXIS)
    await wait_for("U310 back", lambda: "U310" in codes(client, uri) and "xml-syntax" not in codes(client, uri))
    assert not any(d.message.endswith("(from the last text that parsed)") for d in client.diagnostics[uri])

    # `</robot>` deleted: the error is at the end of the file, where the end tag is missing (not line 1).
    unclosed = BROKEN_AXIS.replace("</robot>", "")
    change(client, uri, 4, unclosed)
    await wait_for("the unclosed root", lambda: "xml-syntax" in codes(client, uri))
    [error] = [d for d in client.diagnostics[uri] if d.code == "xml-syntax"]
    last_line = len(unclosed.rstrip().split("\n")) - 1
    assert error.range.start.line == last_line and "never closed" in error.message, error


async def test_a_xacro_library_alone_is_only_checked_to_be_xml(client, tmp_path):
    parts = tmp_path / "parts.xacro"
    parts.write_text(XACRO_PARTS)
    uri = open_file(client, parts)
    await wait_for("parts.xacro published", lambda: any(p.uri == uri for p in client.published))
    assert not client.diagnostics[uri]
    change(client, uri, 2, XACRO_PARTS.replace("</xacro:macro>", "</xacro:macr>"))
    await wait_for("the XML error", lambda: client.diagnostics.get(uri))
    assert "not well-formed" in client.diagnostics[uri][0].message


async def test_a_10_mb_document_and_an_include_cycle_are_diagnostics(client, tmp_path):
    # 10 MB: a small robot after a long comment; its findings come, and requests are answered meanwhile.
    big_text = BROKEN_AXIS.replace("<robot", "<!--" + "x" * (10 << 20) + "-->\n<robot", 1)
    big = tmp_path / "big.urdf"
    big.write_text(big_text)
    uri = open_file(client, big)
    symbols = await client.text_document_document_symbol_async(
        types.DocumentSymbolParams(text_document=types.TextDocumentIdentifier(uri=uri))
    )
    assert [s.name for s in symbols] == ["base"]
    await wait_for("U310 in the 10 MB document", lambda: "U310" in codes(client, uri))
    [axis] = [d for d in client.diagnostics[uri] if d.code == "U310"]
    assert axis.range.start.line == big_text.split("\n").index('    <axis xyz="0 0 2"/>')

    # A xacro include cycle: one error, on the file, naming the cycle.
    (tmp_path / "a.urdf.xacro").write_text(
        '<robot name="a" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<xacro:include filename="b.xacro"/><link name="l"/></robot>'
    )
    (tmp_path / "b.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><xacro:include filename="a.urdf.xacro"/></robot>'
    )
    cycle = open_file(client, tmp_path / "a.urdf.xacro")
    await wait_for("the cycle's error", lambda: [
        p for p in client.published if p.uri in (cycle, (tmp_path / "b.xacro").as_uri()) and p.diagnostics
    ])
    shown = [d for p in client.published for d in p.diagnostics if p.uri != uri]
    assert any(d.severity == types.DiagnosticSeverity.Error and "includ" in d.message for d in shown), shown


async def test_gazebo_links_are_not_the_robots_and_an_orphan_joint_says_why(client, tmp_path):
    # A <gazebo> block with SDFormat links of its own, and a joint whose parent link is not defined.
    text = BROKEN_AXIS.replace(
        "</robot>",
        """  <gazebo>
    <link name="gz_only"/>
  </gazebo>
  <joint name="orphan" type="fixed">
    <parent link="nowhere"/>
    <child link="upper"/>
  </joint>
</robot>""",
    )
    robot = tmp_path / "arm.urdf"
    robot.write_text(text)
    uri = open_file(client, robot)
    await wait_for("U102", lambda: "U102" in codes(client, uri))
    symbols = await client.text_document_document_symbol_async(
        types.DocumentSymbolParams(text_document=types.TextDocumentIdentifier(uri=uri))
    )

    def names(items):
        for item in items:
            yield item.name
            yield from names(item.children or [])

    assert "gz_only" not in set(names(symbols)), list(names(symbols))
    completion = await client.text_document_completion_async(
        types.CompletionParams(
            text_document=types.TextDocumentIdentifier(uri=uri),
            position=position_of(text, '<parent link="', len('<parent link="')),
        )
    )
    labels = {item.label for item in completion}
    assert {"base", "upper"} <= labels and "gz_only" not in labels, labels
    hover = await client.text_document_hover_async(
        types.HoverParams(
            text_document=types.TextDocumentIdentifier(uri=uri),
            position=position_of(text, '<joint name="orphan"', len('<joint name="') + 1),
        )
    )
    assert "parent link `nowhere` is not defined" in hover.contents.value, hover.contents.value
