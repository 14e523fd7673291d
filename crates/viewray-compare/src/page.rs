//! The skeleton every viewray report page shares: the document, its head and the style
//! sheet's common part (type, colours, verdict badges, boxed sections, figures), which
//! the golden check's and `viewray compare`'s report and `viewray grade`'s class report
//! and student pages each complete with their own layout.

use maud::{DOCTYPE, Markup, PreEscaped, html};

use crate::outcome::Verdict;

/// A whole report page: `title` in the head, the common style sheet followed by the
/// page's own `style` (whose rules, coming later, refine the common ones), and `body`.
/// The page carries no timestamp: the same content gives the same bytes.
pub fn report_page(title: &str, style: &str, body: Markup) -> Markup {
    html! {
        (DOCTYPE)
        html lang="en" {
            head {
                meta charset="utf-8";
                title { (title) }
                style { (PreEscaped(STYLE)) (PreEscaped(style)) }
            }
            body { (body) }
        }
    }
}

/// A verdict as a coloured badge, `<span class="verdict fail">FAIL</span>`: green for
/// `PASS`, red for `FAIL`, grey for `ERROR`.
pub fn verdict_badge(verdict: Verdict) -> Markup {
    html! {
        span class={ "verdict " (verdict.word()) } { (verdict.label()) }
    }
}

/// The style sheet's common part.
const STYLE: &str = "
body { font-family: system-ui, sans-serif; color: #222; background: #fafafa; }
.summary { font-weight: bold; }
section { background: #fff; border: 1px solid #ddd; margin: 1em 0; }
.verdict { display: inline-block; padding: 0 0.4em; border-radius: 3px; color: #fff; font-weight: bold; font-size: 0.9em; }
.verdict.pass { background: #2a2; }
.verdict.fail { background: #c22; }
.verdict.error { background: #777; }
.images { display: flex; flex-wrap: wrap; }
figure { margin: 0; }
figure img { border: 1px solid #ccc; display: block; }
figcaption { color: #666; text-align: center; }
";

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_page_holds_its_title_both_style_sheets_in_order_and_its_body() {
        let page =
            report_page("a <b> & c", ".own { color: red; }", html! { p { "hello" } }).into_string();
        assert!(
            page.starts_with("<!DOCTYPE html><html lang=\"en\"><head><meta charset=\"utf-8\">")
        );
        assert!(page.contains("<title>a &lt;b&gt; &amp; c</title>"));
        let common = page.find(".verdict.pass").unwrap();
        let own = page.find(".own { color: red; }").unwrap();
        assert!(
            common < own,
            "the page's own rules come after the common ones"
        );
        assert!(page.ends_with("</style></head><body><p>hello</p></body></html>"));
    }

    #[test]
    fn a_badge_names_its_verdict_in_the_terminals_words() {
        for (verdict, html) in [
            (Verdict::Pass, "<span class=\"verdict pass\">PASS</span>"),
            (Verdict::Fail, "<span class=\"verdict fail\">FAIL</span>"),
            (Verdict::Error, "<span class=\"verdict error\">ERROR</span>"),
        ] {
            assert_eq!(verdict_badge(verdict).into_string(), html);
        }
    }
}
