//! The report's pages: `index.html`, one page per paper, `claims.json`, tables as CSV
//! and JSON, figures as PNG and SVG. Plain HTML and CSS, no scripts.

use std::fmt::Write as _;
use std::path::Path;

use crate::coverage::{self, Status};
use crate::{Claim, Done, Error, Figure, Options, Paper, Scale, Table};

/// Escape text for HTML.
pub fn escape(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

/// Write `bytes` to `path`, an I/O error naming it.
pub(crate) fn write(path: &Path, bytes: &[u8]) -> Result<(), Error> {
    std::fs::write(path, bytes).map_err(|e| crate::io_error(path, e))
}

pub(crate) const STYLE: &str =
    "body{font-family:system-ui,sans-serif;max-width:1100px;margin:2em auto;padding:0 1em;color:#222;line-height:1.45}
h1,h2,h3{line-height:1.2}table{border-collapse:collapse;margin:.8em 0;font-size:.92em}
th,td{border:1px solid #ccc;padding:.3em .6em;text-align:right}th{background:#f3f3f3}
td:first-child,th:first-child,table.claims td,table.claims th{text-align:left}figure{margin:1.2em 0}figure img{max-width:100%;border:1px solid #ddd}
figcaption,.caption{color:#555;font-size:.9em}.reproduced{color:#17692b;font-weight:600}
.not-reproduced{color:#b3261e;font-weight:600}.differs{color:#8a5a00;font-weight:600}
.undecided{color:#5a4b8a;font-weight:600}.checked{color:#2f5f5f;font-weight:600}.contradicted{color:#7a2048;font-weight:600}.shown{color:#555;font-weight:600}.not-attempted{color:#888;font-weight:600}
.criterion{color:#666;font-size:.85em}.addition{color:#0b5f86;font-weight:600}
.note{background:#f8f8f2;border-left:3px solid #bbb;padding:.4em .8em;margin:.5em 0}
.pending{color:#666}code{background:#f3f3f3;padding:0 .2em}nav a{margin-right:1em}
.overview{border-top:1px solid #ddd;margin-top:1.5em}.keys{display:flex;flex-wrap:wrap;gap:1.2em}
.keys figure{flex:1 1 440px;margin:.5em 0}.keys ul{margin:.3em 0;padding-left:1.2em}
";

fn verdict_html(c: &Claim) -> String {
    let name = c.verdict_name();
    let mut h = format!(
        "<span class=\"{}\">{name}</span><br><span class=\"criterion\">criterion: {}</span>",
        name.replace(' ', "-"),
        escape(&c.decision.criterion)
    );
    if let Some(why) = c.explained() {
        let _ = write!(h, "<br><span class=\"differs\">explanation:</span> {}", escape(why));
    }
    h
}

fn claims_table(claims: &[&Claim]) -> String {
    let mut h = String::from(
        "<table class=\"claims\"><tr><th>claim</th><th>published</th><th>ours</th><th>theory</th><th>verdict</th></tr>\n",
    );
    for c in claims {
        let statement = match &c.addition {
            Some(source) => format!(
                "<span class=\"addition\">samplab's addition</span> ({}): {}",
                escape(source),
                escape(&c.statement)
            ),
            None => escape(&c.statement),
        };
        let _ = writeln!(
            h,
            "<tr id=\"claim-{}\"><td>{statement}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
            escape(&c.id),
            escape(&c.published),
            escape(&c.ours),
            escape(&c.theory),
            verdict_html(c)
        );
    }
    h + "</table>\n"
}

/// The coverage table of one paper, and its count per status.
fn coverage_table(items: &[coverage::Item], claims: &[&Claim]) -> (String, [usize; Status::ALL.len()]) {
    let mut counts = [0; Status::ALL.len()];
    let mut h =
        String::from("<table class=\"claims\"><tr><th>item</th><th>what</th><th>status</th><th>where</th></tr>\n");
    for it in items {
        let status = coverage::status(it, claims);
        counts[Status::ALL.iter().position(|s| *s == status).expect("listed")] += 1;
        let place = match (&it.experiment, &it.not_attempted) {
            (Some(e), _) => {
                let mut p = format!("<a href=\"#{e}\">experiment {e}</a>");
                for f in &it.shows {
                    let _ = write!(p, ", <a href=\"#{f}\">{f}</a>");
                }
                for c in &it.claims {
                    let _ = write!(p, ", <a href=\"#claim-{c}\">{c}</a>");
                }
                p
            }
            (None, Some(why)) => escape(why),
            (None, None) => String::new(),
        };
        let _ = writeln!(
            h,
            "<tr><td>{}</td><td>{}</td><td><span class=\"{}\">{}</span></td><td>{place}</td></tr>",
            escape(&it.item),
            escape(&it.what),
            status.name().replace(' ', "-"),
            status.name()
        );
    }
    (h + "</table>\n", counts)
}

fn table_html(t: &Table) -> String {
    let mut h = format!("<table id=\"{}\"><tr>", escape(&t.id));
    for c in &t.columns {
        let _ = write!(h, "<th>{}</th>", escape(c));
    }
    h.push_str("</tr>\n");
    for row in &t.rows {
        h.push_str("<tr>");
        for cell in row {
            let _ = write!(h, "<td>{}</td>", escape(&cell.text()));
        }
        h.push_str("</tr>\n");
    }
    let _ = writeln!(
        h,
        "</table><p class=\"caption\">{} (<a href=\"tables/{id}.csv\">CSV</a>, <a href=\"tables/{id}.json\">JSON</a>)</p>",
        escape(&t.caption),
        id = escape(&t.id)
    );
    h
}

fn table_files(dir: &Path, t: &Table) -> Result<(), Error> {
    let mut csv = samplab::io::csv_line(&t.columns);
    for row in &t.rows {
        // CSV keeps full precision
        csv += &samplab::io::csv_line(row.iter().map(|c| match c {
            crate::Cell::Num { value, .. } => format!("{value:?}"),
            other => other.text(),
        }));
    }
    write(&dir.join(format!("tables/{}.csv", t.id)), csv.as_bytes())?;
    let json = serde_json::to_string_pretty(t).expect("tables are plain data");
    write(&dir.join(format!("tables/{}.json", t.id)), json.as_bytes())
}

fn page(title: &str, nav: &str, body: &str) -> String {
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>{t}</title><link rel=\"stylesheet\" href=\"style.css\"></head>\n<body><nav>{nav}</nav>\n<h1>{t}</h1>\n{body}</body></html>\n",
        t = escape(title)
    )
}

/// On a fast report's index: the claims whose verdict differs in the last recorded
/// full-scale run `full` ([`crate::published::full_scale`]), and those it did not have.
fn full_scale_html(full: &crate::published::FullScale, claims: &[(String, Claim)]) -> String {
    let mut changed = String::new();
    let (mut n, mut missing) = (0, Vec::new());
    for (paper, c) in claims {
        match full.verdicts.get(&format!("{paper}/{}", c.id)) {
            Some(v) if v != c.verdict_name() => {
                n += 1;
                let _ = writeln!(
                    changed,
                    "<tr><td>{paper}</td><td><a href=\"{paper}.html#claim-{id}\">{id}</a></td><td>{}</td><td>{}</td></tr>",
                    c.verdict_name(),
                    escape(v),
                    id = escape(&c.id)
                );
            }
            Some(_) => {}
            None => missing.push(format!("{paper}/{}", c.id)),
        }
    }
    let mut h = format!(
        "<h2>Verdicts at full scale</h2>\n<p>The last full-scale run (<code>samplab reproduce --full</code>, seed {}, {} on {}, {:.0} s) gave {n} of these claims another verdict:</p>\n",
        full.seed,
        escape(&full.date),
        escape(&full.machine),
        full.seconds
    );
    if n > 0 {
        let _ = write!(
            h,
            "<table class=\"claims\"><tr><th>paper</th><th>claim</th><th>fast</th><th>full</th></tr>\n{changed}</table>\n"
        );
    }
    if !missing.is_empty() {
        let _ = writeln!(h, "<p>Not in that run (added since): {}.</p>", escape(&missing.join(", ")));
    }
    h
}

/// The figure lint's findings on the index (`lint.json` lists them too).
fn lint_html(lint: &[String]) -> String {
    if lint.is_empty() {
        return format!(
            "<p>Every figure passes the lint (<code>samplab_report::lint</code>): no two labels overlapping, no legend over data, no two series drawn alike, legend swatches in their series' dash style, no axis over {} decades, every render shown at {} px or wider; no claim prints a number with more than {} significant digits. <a href=\"lint.json\">lint.json</a></p>\n",
            crate::plot::MAX_DECADES,
            crate::lint::MIN_PICTURE_WIDTH,
            crate::lint::MAX_DIGITS
        );
    }
    let mut h = format!("<p class=\"not-reproduced\">{} findings of the figure lint:</p>\n<ul>\n", lint.len());
    for l in lint {
        let _ = writeln!(h, "<li>{}</li>", escape(l));
    }
    h + "</ul>\n"
}

/// The run's timing on the index: each experiment's start and length, the threads, the
/// wall time against the sum of the experiments' times, and the critical path (the
/// longest experiment: they are independent); also written as `timing.json`, in the form
/// of `data/timings.json`, which orders the next runs.
fn timing_html(dir: &Path, results: &[(&Paper, Vec<Done>)], options: &Options, wall: f64) -> Result<String, Error> {
    let mut all: Vec<(String, &Done)> = results
        .iter()
        .flat_map(|(p, done)| done.iter().map(move |d| (format!("{}/{}", p.key, d.experiment), d)))
        .collect();
    let sum: f64 = all.iter().map(|(_, d)| d.seconds).sum();
    let threads = rayon::current_num_threads();
    let scale = if options.scale == Scale::Fast { "fast" } else { "full" };
    let seconds: serde_json::Map<String, serde_json::Value> =
        all.iter().map(|(k, d)| (k.clone(), serde_json::json!((d.seconds * 100.0).round() / 100.0))).collect();
    let json = serde_json::json!({ scale: { "threads": threads, "wall_seconds": wall, "experiments": seconds } });
    write(&dir.join("timing.json"), serde_json::to_string_pretty(&json).expect("plain data").as_bytes())?;
    all.sort_by(|a, b| a.1.started.total_cmp(&b.1.started));
    let longest = all.iter().max_by(|a, b| a.1.seconds.total_cmp(&b.1.seconds));
    let mut h = format!(
        "<h2>Timing</h2>\n<p>{} experiments on {threads} threads, longest first (by <code>data/timings.json</code>): {wall:.1} s of wall time for {sum:.1} s of experiments ({:.2} experiments at once on average). The critical path is the longest experiment, {}: {:.1} s. <a href=\"timing.json\">timing.json</a></p>\n<table><tr><th>experiment</th><th>started (s)</th><th>took (s)</th></tr>\n",
        all.len(),
        sum / wall.max(1e-9),
        longest.map_or(String::new(), |(k, _)| escape(k)),
        longest.map_or(0.0, |(_, d)| d.seconds),
    );
    for (key, d) in &all {
        let _ = writeln!(h, "<tr><td>{}</td><td>{:.1}</td><td>{:.1}</td></tr>", escape(key), d.started, d.seconds);
    }
    Ok(h + "</table>\n")
}

/// A paper's overview on the index: its title and source, its claims by verdict, and its
/// key figures (the coverage items that name one), each with the claims it decides and
/// their verdicts, linked into the paper's page; on a fast report, a claim that the last
/// full-scale run (`full`) decided otherwise shows both verdicts. Errors when a key figure
/// is not a figure of the run (a table has no picture to open with).
fn overview_html(
    paper: &Paper,
    cite: &str,
    items: &[coverage::Item],
    claims: &[&Claim],
    figures: &[&Figure],
    full: Option<&crate::published::FullScale>,
) -> Result<String, Error> {
    let [(paper_claims, of_paper), (additions, of_additions)] = by_origin(claims);
    let mut h = format!(
        "<section class=\"overview\"><h2><a href=\"{key}.html\">{title}</a></h2>\n<p class=\"caption\">{}</p>\n<p>{paper_claims} claims of the paper: {}; {additions} of samplab's additions: {} (<a href=\"{key}.html#claims\">every claim</a>).</p>\n<div class=\"keys\">\n",
        escape(cite),
        verdict_spans(of_paper),
        verdict_spans(of_additions),
        key = paper.key,
        title = escape(paper.title)
    );
    for it in items {
        let Some(fig) = &it.key else { continue };
        let Some(figure) = figures.iter().find(|f| &f.id == fig) else {
            return Err(Error::Coverage {
                paper: paper.key.into(),
                reason: format!("the key figure {fig} of {} is not a figure of the run", it.item),
            });
        };
        let _ = writeln!(
            h,
            "<figure><a href=\"{key}.html#{f}\"><img src=\"figures/{f}.png\" alt=\"{item}\"{size}></a><figcaption><b>{item}</b>: {what}. It decides:<ul>",
            key = paper.key,
            f = escape(fig),
            size = figure.display_width().map_or(" style=\"max-width:100%\"".into(), |w| format!(
                " width=\"{w}\" style=\"image-rendering:pixelated;max-width:100%\""
            )),
            item = escape(&it.item),
            what = escape(&it.what)
        );
        for c in claims.iter().filter(|c| it.claims.contains(&c.id)) {
            let span = |v: &str| format!("<span class=\"{}\">{}</span>", escape(&v.replace(' ', "-")), escape(v));
            let at_full = full
                .and_then(|f| f.verdicts.get(&format!("{}/{}", paper.key, c.id)))
                .filter(|v| v.as_str() != c.verdict_name());
            let verdict = match at_full {
                Some(v) => format!("{} at fast scale, {} at full scale", span(c.verdict_name()), span(v)),
                None => span(c.verdict_name()),
            };
            let _ = writeln!(
                h,
                "<li><a href=\"{}.html#claim-{}\">{}</a>: {verdict}</li>",
                paper.key,
                escape(&c.id),
                escape(&c.statement),
            );
        }
        h.push_str("</ul></figcaption></figure>\n");
    }
    Ok(h + "</div></section>\n")
}

/// The claims of the paper and samplab's additions ([`Claim::addition`]): how many of each,
/// and their counts by verdict ([`crate::tally`]).
fn by_origin(claims: &[&Claim]) -> [(usize, [usize; 5]); 2] {
    [false, true].map(|addition| {
        let mine: Vec<&Claim> = claims.iter().copied().filter(|c| c.addition.is_some() == addition).collect();
        (mine.len(), crate::tally(mine))
    })
}

/// Counts by verdict in words, each in its verdict's colour ("3 reproduced, 1 checked").
fn verdict_spans(counts: [usize; 5]) -> String {
    let parts: Vec<String> = crate::VERDICT_NAMES
        .iter()
        .zip(counts)
        .map(|(name, k)| format!("<span class=\"{}\">{k} {name}</span>", name.replace(' ', "-")))
        .collect();
    parts.join(", ")
}

/// Write every file of the report into `dir`; returns the claims with their paper keys.
pub(crate) fn write_report(
    dir: &Path,
    results: &[(&Paper, Vec<Done>)],
    options: &Options,
    wall: f64,
) -> Result<Vec<(String, Claim)>, Error> {
    write(&dir.join("style.css"), STYLE.as_bytes())?;
    let mut nav = String::from("<a href=\"index.html\">summary</a>");
    for (p, _) in results {
        let _ = write!(nav, "<a href=\"{}.html\">{}</a>", p.key, escape(p.title));
    }
    let full = (options.scale == Scale::Fast).then(crate::published::full_scale);
    let mut all_claims: Vec<(String, Claim)> = Vec::new();
    let mut index_rows = String::new();
    let mut overviews = String::new();
    let mut total_seconds = 0.0;
    let mut lint: Vec<String> = Vec::new();
    for (paper, done) in results {
        let cite = samplab::bibliography::lookup(paper.key).map_or(String::new(), |r| r.citation.to_string());
        let claims: Vec<&Claim> = done.iter().flat_map(|d| &d.output.claims).collect();
        let items = coverage::items(paper.key);
        coverage::check(paper.key, &items, &paper.experiments.iter().map(|e| e.id).collect::<Vec<_>>(), &claims)?;
        let made: Vec<&str> = done
            .iter()
            .flat_map(|d| {
                d.output.figures.iter().map(|f| f.id.as_str()).chain(d.output.tables.iter().map(|t| t.id.as_str()))
            })
            .collect();
        let breaches = coverage::audit(&items, &claims, &made);
        if !breaches.is_empty() {
            return Err(Error::Coverage { paper: paper.key.into(), reason: format!("audit: {}", breaches.join("; ")) });
        }
        let (cov, status_counts) = coverage_table(&items, &claims);
        let figures: Vec<&Figure> = done.iter().flat_map(|d| &d.output.figures).collect();
        overviews.push_str(&overview_html(paper, &cite, &items, &claims, &figures, full.as_ref())?);
        let mut body = format!(
            "<p>{}</p>\n<h2>Coverage</h2>\n<p>Every numbered table and figure of the paper (and the equations it states as results), with the status its claims' verdicts give: reproduced (every claim), differs (a claim not reproduced, with a written explanation), not reproduced, undecided (an interval that cannot decide), checked (every claim derived, not measured: an identity, algebra, a closed form checked against itself or a deterministic sampler at fixed positions; the code agrees with the equation, which reproduces no result), contradicted (no measured claim fails, and a derived one does: the paper's statement is wrong by algebra or an exact computation), shown (drawn or computed, with no statement of the paper to test), or not attempted (and why). Each row links the figures and tables that show it.</p>\n{cov}<h2 id=\"claims\">Claims</h2>\n{}",
            escape(&cite),
            claims_table(&claims)
        );
        for d in done {
            total_seconds += d.seconds;
            experiment_html(dir, d, &mut body, &mut lint)?;
        }
        write(&dir.join(format!("{}.html", paper.key)), page(paper.title, &nav, &body).as_bytes())?;
        index_rows.push_str(&index_row(paper, done.len(), &claims, status_counts));
        all_claims.extend(claims.into_iter().map(|c| (paper.key.to_string(), c.clone())));
    }
    for (paper, c) in &all_claims {
        let texts = [&c.statement, &c.published, &c.ours, &c.theory, &c.decision.criterion];
        for text in texts.into_iter().chain(c.explanation.as_ref()) {
            let findings = crate::lint::printed_numbers(text).into_iter().chain(crate::lint::whitespace_runs(text));
            lint.extend(findings.map(|f| format!("{paper}/{}: {f}", c.id)));
        }
    }
    let refs: Vec<&Claim> = all_claims.iter().map(|(_, c)| c).collect();
    let scale = if options.scale == Scale::Fast { "fast (default)" } else { "full (the papers' own scales)" };
    let body = format!(
        "<p>samplab {} reproduction, scale {scale}, seed {}; experiments took {:.1} s in all. Every number in a table comes from this run, except the published values, which are read from one data file with their sources. Per paper: its key figures, the claims they decide and their verdicts; then the counts, the figure lint, the timing and every claim.</p>\n{overviews}<h2>Summary</h2>\n\
         <table><tr><th rowspan=\"2\">paper</th><th rowspan=\"2\">experiments</th><th colspan=\"5\">claims: the paper's + samplab's additions</th><th colspan=\"8\">numbered tables, figures and result equations</th></tr>\n\
         <tr><th>reproduced</th><th>checked</th><th>not reproduced</th><th>contradicted</th><th>undecided</th><th>reproduced</th><th>differs</th><th>not reproduced</th><th>undecided</th><th>checked</th><th>contradicted</th><th>shown</th><th>pending (not attempted)</th></tr>\n{index_rows}</table>\n\
         {}<h2>Figure lint</h2>\n{}{}<h2>All claims</h2>\n{}<p><a href=\"claims.json\">claims.json</a></p>\n",
        env!("CARGO_PKG_VERSION"),
        options.seed.0,
        total_seconds,
        full.as_ref().map_or(String::new(), |f| full_scale_html(f, &all_claims)),
        lint_html(&lint),
        timing_html(dir, results, options, wall)?,
        claims_table(&refs)
    );
    write(&dir.join("lint.json"), serde_json::to_string_pretty(&lint).expect("plain data").as_bytes())?;
    write_claims_json(dir, &all_claims)?;
    // the index last: a folder with an index is a finished report
    write(&dir.join("index.html"), page("samplab: reproducing the papers", &nav, &body).as_bytes())?;
    Ok(all_claims)
}

/// One experiment's section of its paper's page: heading, notes, tables (their files
/// written) and figures (theirs written); the figures' lint gathered.
fn experiment_html(dir: &Path, d: &Done, body: &mut String, lint: &mut Vec<String>) -> Result<(), Error> {
    let _ = write!(
        body,
        "<h2 id=\"{}\">{}</h2>\n<p class=\"caption\">Parameters: {}. Took {:.1} s.</p>\n",
        d.experiment,
        escape(&d.title),
        escape(&d.parameters),
        d.seconds
    );
    for note in &d.output.notes {
        let _ = writeln!(body, "<p class=\"note\">{}</p>", escape(note));
    }
    for t in &d.output.tables {
        table_files(dir, t)?;
        body.push_str(&table_html(t));
    }
    for f in &d.output.figures {
        body.push_str(&figure_html(dir, f)?);
        lint.extend(f.lint.iter().map(|l| format!("{}: {l}", f.id)));
    }
    Ok(())
}

/// A figure's element, its PNG and SVG files written.
fn figure_html(dir: &Path, f: &Figure) -> Result<String, Error> {
    write(&dir.join(format!("figures/{}.png", f.id)), &f.png)?;
    let id = escape(&f.id);
    let svg_link = match &f.svg {
        Some(svg) => {
            write(&dir.join(format!("figures/{}.svg", f.id)), svg.as_bytes())?;
            format!(" (<a href=\"figures/{id}.svg\">SVG</a>)")
        }
        None => String::new(),
    };
    let size =
        f.display_width().map_or(String::new(), |w| format!(" width=\"{w}\" style=\"image-rendering:pixelated\""));
    Ok(format!(
        "<figure id=\"{id}\"><img src=\"figures/{id}.png\"{size} alt=\"{cap}\"><figcaption>{cap}{svg_link}</figcaption></figure>\n",
        cap = escape(&f.caption)
    ))
}

/// A paper's row of the summary: experiments, claims by verdict, coverage by status.
fn index_row(
    paper: &Paper,
    experiments: usize,
    claims: &[&Claim],
    status_counts: impl IntoIterator<Item = usize>,
) -> String {
    let [(_, of_paper), (_, of_additions)] = by_origin(claims);
    let mut row = format!(
        "<tr><td><a href=\"{key}.html\">{title}</a></td><td>{experiments}</td>",
        key = paper.key,
        title = escape(paper.title)
    );
    for (p, a) in of_paper.iter().zip(of_additions) {
        let _ = if a > 0 { write!(row, "<td>{p} + {a}</td>") } else { write!(row, "<td>{p}</td>") };
    }
    for c in status_counts {
        let _ = write!(row, "<td>{c}</td>");
    }
    row.push_str("</tr>\n");
    row
}

/// claims.json: every claim with its paper, the verdict shown and its explanation.
fn write_claims_json(dir: &Path, all_claims: &[(String, Claim)]) -> Result<(), Error> {
    let claims_json: Vec<serde_json::Value> = all_claims
        .iter()
        .map(|(paper, c)| {
            let mut v = serde_json::to_value(c).expect("claims are plain data");
            v["paper"] = paper.clone().into();
            v["verdict_shown"] = c.verdict_name().into();
            if let Some(why) = c.explained() {
                v["explanation"] = why.into();
            }
            v
        })
        .collect();
    write(&dir.join("claims.json"), serde_json::to_string_pretty(&claims_json).expect("plain data").as_bytes())?;
    Ok(())
}
