"""The editor set-ups in editors/ against the server: the file types each one hands to `urdf_validate
server` are the ones the server analyses, Helix's languages.toml (Helix cannot run here) names the
server's command, and docs/integrations/editors.md shows each recipe file as it is. Neovim's recipes are run in Neovim
itself by test_neovim.py; the VS Code and Zed extensions are built by scripts/build-vscode.sh and
scripts/build-zed.sh."""

import json
import pathlib
import re
import tomllib

from conftest import open_file, wait_for

REPO = pathlib.Path(__file__).parents[4]
EDITORS = REPO / "editors"

BROKEN_URDF = """<?xml version="1.0"?>
<robot name="broken">
  <link name="base"/>
  <joint name="j" type="fixed">
    <parent link="base"/>
    <child link="missing"/>
  </joint>
</robot>
"""


def helix() -> dict:
    return tomllib.loads((EDITORS / "helix" / "languages.toml").read_text())


def helix_language() -> dict:
    [language] = [l for l in helix()["language"] if "urdf-validate" in l.get("language-servers", [])]
    return language


def inside(text: str, before: str, item: str) -> set[str]:
    """The `item` captures in the first `{...}` of `text` after `before` (a Lua table)."""
    start = text.index(before) + len(before)
    table = text[text.index("{", start) : text.index("}", start)]
    return set(re.findall(item, table))


def file_types() -> dict[str, set[str]]:
    """The extensions (without the dot) each editor's set-up gives the server."""
    vscode = json.loads((EDITORS / "vscode" / "package.json").read_text())
    [language] = vscode["contributes"]["languages"]
    zed = json.loads((EDITORS / "zed" / "settings.json").read_text())
    neovim = (EDITORS / "neovim" / "urdf_validate.lua").read_text()
    neovim_0_11 = (EDITORS / "neovim" / "urdf_validate-0.11.lua").read_text()
    return {
        "helix": set(helix_language()["file-types"]),
        "vscode": {e.removeprefix(".") for e in language["extensions"]},
        "zed": set(zed["file_types"]["XML"]),
        # The list the FileType callback checks, and the autocommand's patterns.
        "neovim": inside(neovim, "local extensions =", r'"\.(\w+)"'),
        "neovim patterns": inside(neovim, "pattern =", r'"\*\.(\w+)"'),
        # The filetype table, and the list root_dir checks.
        "neovim 0.11": inside(neovim_0_11, "extension =", r'(\w+) = "xml"'),
        "neovim 0.11 root_dir": inside(neovim_0_11, "for _, extension in ipairs(", r'"\.(\w+)"'),
    }


async def test_the_editors_hand_the_server_the_files_it_analyses(client, tmp_path):
    """Every extension an editor set-up names is analysed (the server publishes its diagnostics); no
    extension they all leave out is (.xml, .launch: opened first, still without a publication once every
    named one has had its)."""
    named = file_types()
    everyone = set.union(*named.values())
    disagree = {editor: sorted(everyone - names) for editor, names in named.items() if names != everyone}
    assert not disagree, f"editor set-ups leave out file types the others name: {disagree}"

    def published(uri):
        return any(params.uri == uri for params in client.published)

    def robot(ext: str) -> str:
        path = tmp_path / f"robot.{ext}"
        path.write_text(BROKEN_URDF)
        return open_file(client, path)

    ignored = [robot(ext) for ext in ("xml", "launch")]
    served = {ext: robot(ext) for ext in sorted(everyone)}
    served["urdf.xacro"] = robot("urdf.xacro")
    for ext, uri in served.items():
        await wait_for(f"the diagnostics of robot.{ext}", lambda: published(uri))
    for uri in ignored:
        assert not published(uri), f"the server analysed {uri}, a file type no editor set-up names"


def test_helix_recipe_starts_the_server():
    config = helix()
    server = config["language-server"]["urdf-validate"]
    assert server["command"] == "urdf_validate", server
    assert server["args"][0] == "server", server
    language = helix_language()
    # Helix's own XML grammar, and a language of its own: Helix's "xml" language names none of these.
    assert language["grammar"] == "xml", language
    assert language["name"] != "xml", language
    assert language["block-comment-tokens"] == {"start": "<!--", "end": "-->"}, language


def test_docs_show_each_recipe_file_as_it_is():
    """docs/integrations/editors.md: after `<!-- file: PATH -->`, the next fenced block is PATH's text."""
    docs = (REPO / "docs" / "integrations" / "editors.md").read_text()
    shown = re.findall(r"<!-- file: (\S+) -->\s*```\w*\n(.*?)```", docs, flags=re.S)
    paths = [path for path, _ in shown]
    for wanted in [
        "editors/neovim/urdf_validate.lua",
        "editors/neovim/urdf_validate-0.11.lua",
        "editors/helix/languages.toml",
        "editors/zed/settings.json",
    ]:
        assert wanted in paths, f"docs/integrations/editors.md does not show {wanted}"
    for path, text in shown:
        assert text == (REPO / path).read_text(), f"docs/integrations/editors.md shows an outdated copy of {path}"
