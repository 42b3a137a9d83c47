//! A self-contained HTML page: inline CSS and SVG, no scripts, no network.

/// Escape text for HTML element content and attribute values.
pub fn escape(s: &str) -> String {
    let mut o = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => o.push_str("&amp;"),
            '<' => o.push_str("&lt;"),
            '>' => o.push_str("&gt;"),
            '"' => o.push_str("&quot;"),
            '\'' => o.push_str("&#39;"),
            _ => o.push(c),
        }
    }
    o
}

/// An HTML report under construction.
#[derive(Debug, Default)]
pub struct Page {
    title: String,
    body: String,
}

const STYLE: &str = "body{font-family:sans-serif;margin:24px auto;max-width:900px;color:#222}\
h1{font-size:22px}h2{font-size:18px;border-bottom:1px solid #ccc;padding-bottom:3px;margin-top:28px}\
table{border-collapse:collapse;margin:8px 0;font-size:13px}td,th{border:1px solid #ccc;padding:3px 8px;text-align:left}\
td.n{text-align:right;font-variant-numeric:tabular-nums}th{background:#f2f2f2}\
.note{font-size:12px;color:#555}.warn{color:#b00;font-weight:bold}figure{margin:10px 0}\
figcaption{font-size:12px;color:#555}svg{max-width:100%;height:auto}";

impl Page {
    /// A page with a title (also the first heading).
    pub fn new(title: &str) -> Page {
        Page {
            title: title.to_string(),
            body: format!("<h1>{}</h1>\n", escape(title)),
        }
    }
    /// Section heading.
    pub fn heading(&mut self, text: &str) {
        self.body.push_str(&format!("<h2>{}</h2>\n", escape(text)));
    }
    /// A paragraph of plain text.
    pub fn para(&mut self, text: &str) {
        self.body.push_str(&format!("<p>{}</p>\n", escape(text)));
    }
    /// A small note.
    pub fn note(&mut self, text: &str) {
        self.body.push_str(&format!("<p class=\"note\">{}</p>\n", escape(text)));
    }
    /// A warning line.
    pub fn warning(&mut self, text: &str) {
        self.body.push_str(&format!("<p class=\"warn\">{}</p>\n", escape(text)));
    }
    /// A two-column key/value table.
    pub fn key_values(&mut self, rows: &[(String, String)]) {
        self.body.push_str("<table>\n");
        for (k, v) in rows {
            self.body.push_str(&format!(
                "<tr><th>{}</th><td class=\"n\">{}</td></tr>\n",
                escape(k),
                escape(v)
            ));
        }
        self.body.push_str("</table>\n");
    }
    /// A table with a header row.
    pub fn table(&mut self, header: &[String], rows: &[Vec<String>]) {
        self.body.push_str("<table>\n<tr>");
        for h in header {
            self.body.push_str(&format!("<th>{}</th>", escape(h)));
        }
        self.body.push_str("</tr>\n");
        for r in rows {
            self.body.push_str("<tr>");
            for c in r {
                // numbers right-aligned, text left-aligned
                let numeric = c.starts_with(|ch: char| ch.is_ascii_digit() || "+-.".contains(ch));
                let class = if numeric { " class=\"n\"" } else { "" };
                self.body.push_str(&format!("<td{class}>{}</td>", escape(c)));
            }
            self.body.push_str("</tr>\n");
        }
        self.body.push_str("</table>\n");
    }
    /// An inline SVG figure with an id (for tests and links) and a caption.
    pub fn figure(&mut self, id: &str, svg: &str, caption: &str) {
        // drop an XML declaration if the backend wrote one: not allowed inside HTML
        let svg = match svg.find("<svg") {
            Some(i) => &svg[i..],
            None => svg,
        };
        self.body.push_str(&format!(
            "<figure id=\"{}\">\n{}\n<figcaption>{}</figcaption>\n</figure>\n",
            escape(id),
            svg.trim(),
            escape(caption)
        ));
    }
    /// The finished document.
    pub fn finish(&self) -> String {
        format!(
            "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>{}</title>\n<style>{}</style>\n</head>\n<body>\n{}<p class=\"note\">drillpath {}</p>\n</body>\n</html>\n",
            escape(&self.title),
            STYLE,
            self.body,
            env!("CARGO_PKG_VERSION")
        )
    }
}

/// Check a finished report: no "NaN" or "inf" anywhere in numbers (reports must never show them).
pub fn check_finite_text(html: &str) -> Result<(), String> {
    for bad in ["NaN", "inf"] {
        for (i, _) in html.match_indices(bad) {
            // "inf" inside words (e.g. "information", "infinite") is fine; a number is not
            let before = html[..i].chars().next_back();
            let after = html[i + bad.len()..].chars().next();
            let word = |c: Option<char>| c.is_some_and(|c| c.is_ascii_alphabetic());
            if !word(before) && !word(after) {
                return Err(format!("report contains `{bad}` near byte {i}"));
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn escapes_markup_and_rejects_non_finite_numbers() {
        assert_eq!(escape("a<b & \"c\""), "a&lt;b &amp; &quot;c&quot;");
        assert!(check_finite_text("<td>NaN kN</td>").is_err());
        assert!(check_finite_text("<td>-inf</td>").is_err());
        assert!(check_finite_text("<p>information, infinite</p>").is_ok());
    }
}
