//! The viewer's page: one self-contained HTML file holding its style, its WebGL renderer
//! (`assets/view/view.js`, compiled into the binary) and the scene as JSON. It loads nothing
//! else, so it works from a file with the network off.

use serde_json::Value;

/// The page's frame: the panels and the style, with `/*VCNC_SCRIPT*/` and `/*VCNC_DATA*/`
/// where the renderer and the scene go.
const TEMPLATE: &str = include_str!("../../assets/view/view.html");

/// The renderer: a hand-written WebGL 1 program (no library).
const SCRIPT: &str = include_str!("../../assets/view/view.js");

/// The page showing `scene` (the JSON of [`super::scene::Scene::to_json`]).
pub(crate) fn html(scene: &Value) -> String {
    // Inside a <script> element only `</script` (or `<!--`) ends or bends the text: JSON has
    // `<` only within strings, where `\u003c` reads the same.
    let data = scene.to_string().replace('<', "\\u003c");
    TEMPLATE
        .replacen("/*VCNC_SCRIPT*/", SCRIPT, 1)
        .replacen("/*VCNC_DATA*/", &data, 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn program_text_cannot_end_the_script_element() {
        let page = html(&serde_json::json!({ "name": "</script><b>x</b>" }));
        assert!(!page.contains("</script><b>"));
        assert!(page.contains(r#"\u003c/script>\u003cb>"#));
    }

    #[test]
    fn the_page_holds_the_renderer_and_the_data_once() {
        let page = html(&serde_json::json!({ "name": "p" }));
        assert!(page.contains("vcncView"));
        assert!(!page.contains("/*VCNC_SCRIPT*/") && !page.contains("/*VCNC_DATA*/"));
    }
}
