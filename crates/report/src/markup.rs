//! The pieces of HTML both the page ([`crate::html`]) and a fault scene's sections
//! ([`crate::fault_page`]) are written with.

use crate::summary::Figure;

/// Escapes text for HTML.
pub(crate) fn esc(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

/// A figure as the page shows it: heading, image and caption.
pub(crate) fn figure_html(f: &Figure) -> String {
    format!(
        "<figure id=\"{id}\">\n<h3>{title}</h3>\n<img src=\"figures/{file}\" alt=\"{title}\">\n<figcaption>{caption}</figcaption>\n</figure>\n",
        id = esc(f.file.trim_end_matches(".png")),
        title = esc(&f.title),
        file = esc(&f.file),
        caption = esc(&f.caption)
    )
}
