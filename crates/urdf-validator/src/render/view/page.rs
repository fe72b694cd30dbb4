//! The pages that draw a [`Scene`](super::Scene): the live page `urdf_validate view` serves (scene and poses fetched
//! from the server) and the section the HTML report embeds (scene inline, the report's pose).

/// three.js, OrbitControls and `viewer.js`, bundled by `scripts/vendor-three.sh`.
pub const BUNDLE: &str = include_str!("viewer.min.js");

/// The view's style, shared by the live page and the report.
pub const CSS: &str = include_str!("viewer.css");

/// The page `urdf_validate view` serves: it fetches `/scene.json` (asked for before the bundle is read, so
/// the two overlap), posts poses to `/pose` and polls `/version` to reload when the file changes.
pub fn live_page(title: &str) -> String {
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>{} — urdf_validate view</title>\n\
         <script>const urdfViewPending = fetch(\"/scene.json\");</script>\n\
         <style>html,body{{margin:0;height:100%;font:14px system-ui,sans-serif}}.urdf-view{{height:100vh}}{CSS}</style>\n</head>\n<body>\n\
         <div id=\"view\" class=\"urdf-view\"></div>\n<script>{}</script>\n\
         <script>UrdfView.mount(document.getElementById(\"view\"), {{sceneUrl: \"/scene.json\", poseUrl: \"/pose\", versionUrl: \"/version\", pending: urdfViewPending}});</script>\n\
         </body>\n</html>\n",
        crate::render::html::escape(title),
        script_safe(BUNDLE),
    )
}

/// The HTML report's 3-D section: the scene (JSON of a [`super::Scene`]) and the bundle inline, the
/// report's pose.
pub fn embedded_section(json: &str) -> String {
    format!(
        "<section class=\"view3d\" aria-label=\"3-D view\"><h2>Robot</h2>\n<div id=\"view3d\" class=\"urdf-view\"></div>\n\
         <script type=\"application/json\" id=\"view3d-scene\">{}</script>\n<script>{}</script>\n\
         <script>UrdfView.mount(document.getElementById(\"view3d\"), {{scene: JSON.parse(document.getElementById(\"view3d-scene\").textContent)}});</script>\n</section>\n",
        json_in_html(json),
        script_safe(BUNDLE),
    )
}

/// JSON safe anywhere in HTML: `<`, `>` and `&` as JSON escapes (the same string to a JSON parser), so
/// no name from the robot file appears as markup, even inside the script element that holds it.
fn json_in_html(json: &str) -> String {
    json.replace('<', "\\u003c")
        .replace('>', "\\u003e")
        .replace('&', "\\u0026")
}

/// `text` safe inside a `<script>` element: no `</` can end it early (`<\/` means the same in JSON and in
/// JavaScript strings; the bundle has none outside strings).
fn script_safe(text: &str) -> String {
    text.replace("</", "<\\/")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_in_the_embedded_scene_are_not_markup() {
        let section = embedded_section("{\"robot\":\"</script><img src=x onerror=alert(1)>&\"}");
        assert!(section
            .contains("\\u003c/script\\u003e\\u003cimg src=x onerror=alert(1)\\u003e\\u0026"));
        assert!(!section.contains("<img"));
    }

    #[test]
    fn a_closing_tag_in_a_name_cannot_end_the_script() {
        assert_eq!(
            script_safe("{\"name\":\"</script><b>\"}"),
            "{\"name\":\"<\\/script><b>\"}"
        );
        assert!(!live_page("</title><script>").contains("</title><script>"));
    }
}
