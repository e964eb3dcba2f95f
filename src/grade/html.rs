//! The self-contained HTML report: the table, the ranking and inline SVG plots (ticks to
//! complete per map, the ranking); no scripts, no external style sheets, fonts or images.

use super::table::{self, Rank, Row};
use super::tournament::{self, Standing};
use super::Report;
use std::fmt::Write;

/// Colours of the submissions' bars, in class order (cycled).
const PALETTE: &[&str] = &[
    "#4e79a7", "#f28e2b", "#e15759", "#76b7b2", "#59a14f", "#edc948", "#b07aa1", "#ff9da7",
    "#9c755f", "#bab0ac",
];

const STYLE: &str = "body{font-family:sans-serif;margin:2em;color:#222}\
table{border-collapse:collapse;margin:1em 0}\
th,td{border:1px solid #ccc;padding:.3em .6em;text-align:left}\
th{background:#f0f0f0}td.n{text-align:right}\
svg{display:block;margin:1em 0}svg text{font-size:12px}";

/// `s` with `&`, `<`, `>`, `"` and `'` escaped.
pub fn escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            c => out.push(c),
        }
    }
    out
}

/// The whole report as one HTML document.
pub fn report(r: &Report) -> String {
    let mut h = String::new();
    let title = if r.standings.is_empty() {
        "goal grade"
    } else {
        "goal grade: tournament"
    };
    let _ = write!(
        h,
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\"/>\n\
         <title>{title}</title>\n<style>{STYLE}</style>\n</head>\n<body>\n<h1>{title}</h1>\n"
    );
    let list = |v: Vec<String>| escape(&v.join(", "));
    let _ = writeln!(
        h,
        "<p>Maps: {}; robots: {}; seeds: {}.</p>",
        list(r.maps.clone()),
        list(r.robots.iter().map(|x| x.to_string()).collect()),
        list(r.seeds.iter().map(|x| x.to_string()).collect()),
    );
    if r.standings.is_empty() {
        h.push_str("<h2>Results per submission and map</h2>\n");
        h.push_str(&html_table(table::CSV_HEADER, &cells(&r.table)));
        h.push_str("<h2>Ticks to complete per map</h2>\n");
        h.push_str(&ticks_plot(&r.table, &r.ranking));
        h.push_str("<h2>Ranking</h2>\n");
        h.push_str(&ranking_plot(&r.ranking));
    } else {
        h.push_str("<h2>Standings</h2>\n");
        let rows: Vec<Vec<String>> = r.standings.iter().map(Standing::cells).collect();
        h.push_str(&html_table(tournament::CSV_HEADER, &rows));
        h.push_str(&standings_plot(&r.standings));
    }
    h.push_str("</body>\n</html>\n");
    h
}

fn cells(rows: &[Row]) -> Vec<Vec<String>> {
    rows.iter().map(Row::cells).collect()
}

fn html_table(header: &[&str], rows: &[Vec<String>]) -> String {
    let mut h = String::from("<table>\n<thead><tr>");
    for c in header {
        let _ = write!(h, "<th>{}</th>", escape(c));
    }
    h.push_str("</tr></thead>\n<tbody>\n");
    for r in rows {
        h.push_str("<tr>");
        for c in r {
            let numeric = !c.is_empty() && c.parse::<f64>().is_ok();
            let class = if numeric { " class=\"n\"" } else { "" };
            let _ = write!(h, "<td{class}>{}</td>", escape(c));
        }
        h.push_str("</tr>\n");
    }
    h.push_str("</tbody>\n</table>\n");
    h
}

/// The colour of `name`: by its place in `order`.
fn colour(order: &[&str], name: &str) -> &'static str {
    let i = order.iter().position(|n| *n == name).unwrap_or(0);
    PALETTE[i % PALETTE.len()]
}

/// Grouped bars: one group per map, one bar per submission (ticks to complete; runs that
/// never completed have no bar and say so).
fn ticks_plot(rows: &[Row], ranking: &[Rank]) -> String {
    let mut names: Vec<&str> = ranking.iter().map(|r| r.submission.as_str()).collect();
    names.sort_unstable();
    let maps: Vec<&str> = {
        let mut m: Vec<&str> = Vec::new();
        for r in rows.iter().filter(|r| r.map != "-") {
            if !m.contains(&r.map.as_str()) {
                m.push(&r.map);
            }
        }
        m
    };
    let max = rows
        .iter()
        .filter_map(|r| r.ticks_to_complete)
        .fold(1.0f64, f64::max);
    let (bar, gap, plot_h, left, top) = (18.0, 24.0, 200.0, 60.0, 20.0);
    let group = bar * names.len().max(1) as f64 + gap;
    let width = left + group * maps.len().max(1) as f64 + 160.0;
    let height = top + plot_h + 40.0;
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width}\" height=\"{height}\" \
         role=\"img\" aria-label=\"ticks to complete per map\">\n"
    );
    let _ = writeln!(
        s,
        "<line x1=\"{left}\" y1=\"{top}\" x2=\"{left}\" y2=\"{}\" stroke=\"#444\"/>\
         <text x=\"{}\" y=\"{}\" text-anchor=\"end\">{max}</text>\
         <text x=\"{}\" y=\"{}\" text-anchor=\"end\">0</text>",
        top + plot_h,
        left - 4.0,
        top + 10.0,
        left - 4.0,
        top + plot_h
    );
    for (g, map) in maps.iter().enumerate() {
        let x0 = left + gap / 2.0 + g as f64 * group;
        for (k, name) in names.iter().enumerate() {
            let x = x0 + k as f64 * bar;
            let row = rows.iter().find(|r| r.map == *map && r.submission == *name);
            match row.and_then(|r| r.ticks_to_complete) {
                Some(t) => {
                    let h = t / max * plot_h;
                    let _ = writeln!(
                        s,
                        "<rect x=\"{x}\" y=\"{}\" width=\"{}\" height=\"{h}\" fill=\"{}\">\
                         <title>{} on {}: {t} ticks</title></rect>",
                        top + plot_h - h,
                        bar - 2.0,
                        colour(&names, name),
                        escape(name),
                        escape(map)
                    );
                }
                None => {
                    let _ = writeln!(
                        s,
                        "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\" fill=\"#999\">-\
                         <title>{} on {}: never completed</title></text>",
                        x + bar / 2.0,
                        top + plot_h - 4.0,
                        escape(name),
                        escape(map)
                    );
                }
            }
        }
        let _ = writeln!(
            s,
            "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>",
            x0 + bar * names.len() as f64 / 2.0,
            top + plot_h + 16.0,
            escape(short_map(map))
        );
    }
    let lx = left + group * maps.len().max(1) as f64 + 10.0;
    for (k, name) in names.iter().enumerate() {
        let y = top + k as f64 * 16.0;
        let _ = writeln!(
            s,
            "<rect x=\"{lx}\" y=\"{y}\" width=\"10\" height=\"10\" fill=\"{}\"/>\
             <text x=\"{}\" y=\"{}\">{}</text>",
            colour(&names, name),
            lx + 14.0,
            y + 10.0,
            escape(name)
        );
    }
    s.push_str("</svg>\n");
    s
}

/// A map file's name without directory and extension (a plot label); names stay as they are.
fn short_map(map: &str) -> &str {
    let name = map.rsplit(['/', '\\']).next().unwrap_or(map);
    name.rsplit_once('.').map_or(name, |(stem, _)| stem)
}

/// Horizontal bars, one per submission in ranking order (length: completion rate).
fn ranking_plot(ranking: &[Rank]) -> String {
    let labels: Vec<String> = ranking
        .iter()
        .map(|r| {
            let ticks = r
                .ticks_to_complete
                .map_or_else(|| "never completed".to_string(), |t| format!("{t} ticks"));
            format!("{:.0}% completed, {ticks}", r.completion_rate * 100.0)
        })
        .collect();
    let bars: Vec<(String, f64, String)> = ranking
        .iter()
        .zip(labels)
        .map(|(r, l)| {
            (
                format!("{}. {}", r.rank, r.submission),
                r.completion_rate,
                l,
            )
        })
        .collect();
    hbars("ranking", &bars, 1.0)
}

/// Horizontal bars of the tournament's scores (right deliveries).
fn standings_plot(standings: &[Standing]) -> String {
    let max = standings
        .iter()
        .map(|s| s.deliveries_right)
        .max()
        .unwrap_or(0)
        .max(1) as f64;
    let bars: Vec<(String, f64, String)> = standings
        .iter()
        .map(|s| {
            (
                format!("{}. {}", s.rank, s.submission),
                s.deliveries_right as f64,
                format!("{} right deliveries, {} wins", s.deliveries_right, s.wins),
            )
        })
        .collect();
    hbars("tournament standings", &bars, max)
}

/// Labelled horizontal bars `(label, value, note)` scaled to `max`.
fn hbars(what: &str, bars: &[(String, f64, String)], max: f64) -> String {
    let (left, width, row) = (180.0, 300.0, 22.0);
    let height = row * bars.len().max(1) as f64 + 10.0;
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{}\" height=\"{height}\" \
         role=\"img\" aria-label=\"{}\">\n",
        left + width + 220.0,
        escape(what)
    );
    for (i, (label, value, note)) in bars.iter().enumerate() {
        let y = 5.0 + i as f64 * row;
        let w = if max > 0.0 { value / max * width } else { 0.0 };
        let _ = writeln!(
            s,
            "<text x=\"{}\" y=\"{}\" text-anchor=\"end\">{}</text>\
             <rect x=\"{left}\" y=\"{y}\" width=\"{w}\" height=\"{}\" fill=\"{}\"/>\
             <text x=\"{}\" y=\"{}\">{}</text>",
            left - 6.0,
            y + 13.0,
            escape(label),
            row - 6.0,
            PALETTE[0],
            left + w + 6.0,
            y + 13.0,
            escape(note)
        );
    }
    s.push_str("</svg>\n");
    s
}

#[cfg(test)]
mod tests {
    #[test]
    fn map_files_are_labelled_by_their_stem() {
        assert_eq!(super::short_map("maps/two-rooms.toml"), "two-rooms");
        assert_eq!(super::short_map("banana"), "banana");
    }

    #[test]
    fn text_is_escaped() {
        assert_eq!(
            super::escape("<b>&\"x'</b>"),
            "&lt;b&gt;&amp;&quot;x&#39;&lt;/b&gt;"
        );
    }
}
