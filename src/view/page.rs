//! The page, built into the binary: plain HTML, CSS and JavaScript (no build step, no network
//! access; the drawing is SVG made from the trace's data).

/// The page's files: `(path, content, content type)`.
const ASSETS: &[(&str, &str, &str)] = &[
    (
        "/",
        include_str!("page/index.html"),
        "text/html; charset=utf-8",
    ),
    (
        "/index.html",
        include_str!("page/index.html"),
        "text/html; charset=utf-8",
    ),
    (
        "/view.css",
        include_str!("page/view.css"),
        "text/css; charset=utf-8",
    ),
    (
        "/view.js",
        include_str!("page/view.js"),
        "text/javascript; charset=utf-8",
    ),
    (
        "/player.js",
        include_str!("page/player.js"),
        "text/javascript; charset=utf-8",
    ),
    (
        "/player.css",
        include_str!("page/player.css"),
        "text/css; charset=utf-8",
    ),
];

/// The content and content type of the page file at `path`.
pub fn asset(path: &str) -> Option<(&'static str, &'static str)> {
    ASSETS
        .iter()
        .find(|(p, _, _)| *p == path)
        .map(|(_, body, kind)| (*body, *kind))
}
