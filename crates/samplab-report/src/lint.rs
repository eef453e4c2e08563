//! The figure lint, run on every figure the report writes: what a reader would see wrong;
//! and the claims' texts, for numbers printed past their precision ([`printed_numbers`]) and
//! runs of white space ([`whitespace_runs`]).
//! The chart checks what its specification shows ([`crate::plot::Drawable::lint`]: two
//! series drawn alike, an axis spanning more than [`crate::plot::MAX_DECADES`] decades);
//! this module reads the SVG as drawn: no two text labels overlapping or touching, no
//! legend box over plotted data, every legend swatch in its series' dash style. Pictures
//! (renders) are displayed at [`MIN_PICTURE_WIDTH`] px or more.
//!
//! The SVG is plotters' own output: one element per line, text content on the line after
//! its `<text>` tag, the legend a translucent (`opacity="0.85"`) white rectangle drawn
//! after the data.

/// The most significant digits a decimal number may be printed with: a float printed with
/// more (`0.8306999999999998`, `0.6931471805599453`) shows its binary rounding, not a
/// measured or published precision.
pub const MAX_DIGITS: usize = 12;

/// Each decimal number in `text` (one with a point or an exponent: integers are exact)
/// printed with more than [`MAX_DIGITS`] significant digits, as a finding.
pub fn printed_numbers(text: &str) -> Vec<String> {
    let bytes = text.as_bytes();
    let mut found = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        // a number starts at a digit that does not continue a word (`x86`, `d2`)
        if !bytes[i].is_ascii_digit() || (i > 0 && (bytes[i - 1].is_ascii_alphanumeric() || bytes[i - 1] == b'_')) {
            i += 1;
            continue;
        }
        let start = i;
        while i < bytes.len() && (bytes[i].is_ascii_digit() || bytes[i] == b'.') {
            i += 1;
        }
        let mantissa = &text[start..i];
        let exponent = i + 1 < bytes.len() && matches!(bytes[i], b'e' | b'E') && {
            let j = i + 1 + usize::from(matches!(bytes[i + 1], b'-' | b'+'));
            j < bytes.len() && bytes[j].is_ascii_digit()
        };
        if !(mantissa.contains('.') || exponent) {
            continue;
        }
        let digits = mantissa.trim_start_matches(['0', '.']).chars().filter(char::is_ascii_digit).count();
        if digits > MAX_DIGITS {
            found.push(format!(
                "'{mantissa}' printed with {digits} significant digits (over {MAX_DIGITS}): a float past its precision"
            ));
        }
    }
    found
}

/// The narrowest a render is displayed on the page, in CSS pixels: smaller ones are
/// enlarged by an integer factor, nearest neighbour, so that banding and noise stay visible.
pub const MIN_PICTURE_WIDTH: u32 = 256;

/// The integer factor by which a picture `width` px wide is enlarged on the page.
pub fn picture_scale(width: u32) -> u32 {
    MIN_PICTURE_WIDTH.div_ceil(width.max(1)).max(1)
}

/// The value of attribute `name` in `tag`.
fn attr<'a>(tag: &'a str, name: &str) -> Option<&'a str> {
    let key = format!(" {name}=\"");
    let at = tag.find(&key)? + key.len();
    tag[at..].split('"').next()
}

fn num(tag: &str, name: &str) -> f64 {
    attr(tag, name).and_then(|v| v.parse().ok()).unwrap_or(0.0)
}

/// A text label's box on the page.
#[derive(Debug, Clone, PartialEq)]
struct Label {
    text: String,
    x0: f64,
    y0: f64,
    x1: f64,
    y1: f64,
    size: f64,
}

/// The box of a `<text>` tag holding `text`: DejaVu Sans advances about 0.62 em per
/// character; the vertical place follows plotters' `dy` (top, middle or bottom anchor).
fn label(tag: &str, text: &str) -> Label {
    let (x, y, size) = (num(tag, "x"), num(tag, "y"), num(tag, "font-size").max(1.0));
    let width = 0.62 * size * text.chars().count() as f64;
    let left = match attr(tag, "text-anchor") {
        Some("middle") => x - width / 2.0,
        Some("end") => x - width,
        _ => x,
    };
    let top = match attr(tag, "dy") {
        Some("0.76em") => y,
        Some("0.5ex") => y - size / 2.0,
        Some("-0.5ex") => y - size,
        _ => y - 0.8 * size,
    };
    let (x0, y0, x1, y1) = (left, top, left + width, top + size);
    if attr(tag, "transform").is_some_and(|t| t.starts_with("rotate(270") || t.starts_with("rotate(90")) {
        // a vertical label turns about (x, y)
        let (dx0, dy0, dx1, dy1) = (x0 - x, y0 - y, x1 - x, y1 - y);
        return Label { text: text.into(), x0: x + dy0, y0: y - dx1, x1: x + dy1, y1: y - dx0, size };
    }
    Label { text: text.into(), x0, y0, x1, y1, size }
}

/// Two labels overlap or come closer than a third of an em along the line they share.
fn collide(a: &Label, b: &Label) -> bool {
    let gap = 0.33 * a.size.max(b.size);
    a.x0 < b.x1 + gap && b.x0 < a.x1 + gap && a.y0 < b.y1 && b.y0 < a.y1
}

/// A data mark: its colour, stroke width and vertices.
struct Mark {
    colour: String,
    width: f64,
    points: Vec<(f64, f64)>,
}

fn is_data_colour(c: &str) -> bool {
    let c = c.trim_start_matches('#');
    let Ok(v) = u32::from_str_radix(c, 16) else { return false };
    let (r, g, b) = (v >> 16, (v >> 8) & 255, v & 255);
    // black axes and ticks, white, and the grey mesh and strata lines are not data
    !(r == g && g == b)
}

fn mark(tag: &str) -> Option<Mark> {
    if tag.starts_with("<circle") {
        let colour = attr(tag, "fill").filter(|c| *c != "none").or_else(|| attr(tag, "stroke"))?;
        let (x, y, r) = (num(tag, "cx"), num(tag, "cy"), num(tag, "r"));
        let points = vec![(x - r, y), (x + r, y), (x, y - r), (x, y + r), (x, y)];
        return is_data_colour(colour).then(|| Mark { colour: colour.into(), width: 0.0, points });
    }
    if tag.starts_with("<polyline") {
        let colour = attr(tag, "stroke")?;
        let points = attr(tag, "points")?
            .split_whitespace()
            .filter_map(|p| p.split_once(',').and_then(|(x, y)| Some((x.parse().ok()?, y.parse().ok()?))))
            .collect();
        return is_data_colour(colour).then(|| Mark { colour: colour.into(), width: num(tag, "stroke-width"), points });
    }
    None
}

/// Whether the segment a-b meets the box (x0, y0, x1, y1), by sampling it every pixel.
fn crosses(a: (f64, f64), b: (f64, f64), (x0, y0, x1, y1): (f64, f64, f64, f64)) -> bool {
    let steps = ((b.0 - a.0).abs().max((b.1 - a.1).abs()).ceil() as usize).clamp(1, 4000);
    (0..=steps).any(|k| {
        let t = k as f64 / steps as f64;
        let (x, y) = (a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1));
        x > x0 && x < x1 && y > y0 && y < y1
    })
}

/// Everything the lint finds in one SVG drawing.
pub fn svg(svg: &str) -> Vec<String> {
    let lines: Vec<&str> = svg.lines().map(str::trim).collect();
    let mut labels: Vec<Label> = Vec::new();
    let mut data: Vec<Mark> = Vec::new();
    let mut in_legend: Vec<Mark> = Vec::new();
    let mut legend: Option<(f64, f64, f64, f64)> = None;
    for (i, tag) in lines.iter().enumerate() {
        if tag.starts_with("<text") {
            let text = lines.get(i + 1).copied().unwrap_or("").to_string();
            if !text.is_empty() && !text.starts_with('<') {
                let l = label(tag, &text);
                // plotters draws an axis's last tick twice in one place: one label
                if !labels.contains(&l) {
                    labels.push(l);
                }
            }
        } else if tag.starts_with("<rect") && attr(tag, "opacity") == Some("0.85") {
            let (x, y) = (num(tag, "x"), num(tag, "y"));
            legend = Some((x, y, x + num(tag, "width"), y + num(tag, "height")));
        } else if let Some(m) = mark(tag) {
            if legend.is_some() { in_legend.push(m) } else { data.push(m) }
        }
    }
    let mut found = Vec::new();
    for (i, a) in labels.iter().enumerate() {
        for b in &labels[..i] {
            if collide(a, b) {
                found.push(format!("labels '{}' and '{}' overlap", b.text, a.text));
            }
        }
    }
    if let Some(area) = legend {
        let covered = data.iter().filter(|m| {
            m.points.windows(2).any(|w| crosses(w[0], w[1], area))
                || m.points.len() == 1 && crosses(m.points[0], m.points[0], area)
        });
        if let Some(m) = covered.into_iter().next() {
            found.push(format!("the legend box covers data (a {} mark)", m.colour));
        }
        // a colour drawn dashed (many slanted or level two-point strokes of width 2; error
        // bars are vertical ones) needs a dashed swatch (two strokes or more on one row of
        // the legend)
        let mut colours: Vec<&str> = data.iter().map(|m| m.colour.as_str()).collect();
        colours.dedup();
        for c in colours {
            let dashes = data
                .iter()
                .filter(|m| m.colour == c && m.width == 2.0 && m.points.len() == 2 && m.points[0].0 != m.points[1].0)
                .count();
            let rows: Vec<f64> =
                in_legend.iter().filter(|m| m.colour == c && m.width == 2.0).map(|m| m.points[0].1).collect();
            let dashed_swatch = rows.iter().any(|y| rows.iter().filter(|z| *z == y).count() >= 2);
            if dashes >= 4 && !dashed_swatch {
                found.push(format!("the {c} series is dashed but its legend swatch is not"));
            }
        }
    }
    found
}

/// Each run of white space in `text` other than one space (two or more spaces, a tab, a
/// line break: a claim's text is one paragraph, and a run is what a string literal broken
/// across source lines leaves), as a finding naming the words before it.
pub fn whitespace_runs(text: &str) -> Vec<String> {
    let mut found = Vec::new();
    let mut at = 0;
    while let Some(start) = text[at..].find(char::is_whitespace).map(|i| at + i) {
        let end = text[start..].find(|c: char| !c.is_whitespace()).map_or(text.len(), |i| start + i);
        if &text[start..end] != " " {
            // the last 24 characters of the words before, runs shown as one space
            let words = text[..start].split_whitespace().collect::<Vec<_>>().join(" ");
            let before: String = words.chars().skip(words.chars().count().saturating_sub(24)).collect();
            found
                .push(format!("a run of {} white-space characters after '{before}'", text[start..end].chars().count()));
        }
        at = end;
    }
    found
}

#[cfg(test)]
mod tests {
    use super::*;

    fn text(x: u32, y: u32, s: &str) -> String {
        format!("<text x=\"{x}\" y=\"{y}\" dy=\"0.76em\" text-anchor=\"middle\" font-size=\"10.5\">\n{s}\n</text>\n")
    }

    #[test]
    fn two_touching_tick_labels_are_found() {
        // "9000" and "10000" centred 32 px apart at 10.5 px: 26 and 33 px wide, 2 px apart
        let bad = format!("<svg>\n{}{}</svg>", text(811, 518, "9000"), text(843, 518, "10000"));
        assert_eq!(svg(&bad), vec!["labels '9000' and '10000' overlap".to_string()]);
        let good = format!("<svg>\n{}{}</svg>", text(700, 518, "5000"), text(843, 518, "10000"));
        assert!(svg(&good).is_empty());
        // the same label drawn twice in one place is one label
        let twice = format!("<svg>\n{}{}</svg>", text(843, 518, "10000"), text(843, 518, "10000"));
        assert!(svg(&twice).is_empty());
    }

    #[test]
    fn a_legend_over_data_and_a_solid_swatch_for_a_dashed_series_are_found() {
        let dash =
            |x: u32| format!("<polyline stroke=\"#1F77B4\" stroke-width=\"2\" points=\"{x},100 {},100 \"/>\n", x + 6);
        let dashes: String = (0..10).map(|k| dash(100 + 10 * k)).collect();
        let legend = |x: u32| {
            format!("<rect x=\"{x}\" y=\"90\" width=\"50\" height=\"20\" opacity=\"0.85\" fill=\"#FFFFFF\"/>\n")
        };
        let swatch = "<polyline stroke=\"#1F77B4\" stroke-width=\"2\" points=\"610,100 630,100 \"/>\n";
        let over = format!("<svg>\n{dashes}{}{swatch}</svg>", legend(120));
        let found = svg(&over);
        assert!(found.iter().any(|f| f.contains("legend box covers data")), "{found:?}");
        assert!(found.iter().any(|f| f.contains("swatch is not")), "{found:?}");
        let dashed_swatch = "<polyline stroke=\"#1F77B4\" stroke-width=\"2\" points=\"610,100 617,100 \"/>\n\
                             <polyline stroke=\"#1F77B4\" stroke-width=\"2\" points=\"621,100 628,100 \"/>\n";
        assert!(svg(&format!("<svg>\n{dashes}{}{dashed_swatch}</svg>", legend(600))).is_empty());
    }

    #[test]
    fn numbers_printed_past_their_precision_are_found() {
        let found = printed_numbers("-0.8306999999999998 in [-0.134, 0.046]; ln 2 = 0.6931471805599453");
        assert_eq!(found.len(), 2, "{found:?}");
        assert!(found[0].starts_with("'0.8306999999999998' printed with 16 significant digits"), "{found:?}");
        // what is fine: short decimals, exponents, long integers (seeds), digits in words
        for fine in ["0.046 and 1.2e-12", "seed 18446744073709551615", "x86_64 d12345678901234.5", "0.000000123456"] {
            assert!(printed_numbers(fine).is_empty(), "{fine}: {:?}", printed_numbers(fine));
        }
        assert_eq!(printed_numbers("1.23456789012345e-7").len(), 1);
    }

    #[test]
    fn white_space_runs_are_found() {
        let found = whitespace_runs("lattices,                       Kronecker and\n Sobol'");
        assert_eq!(found.len(), 2, "{found:?}");
        assert_eq!(found[0], "a run of 23 white-space characters after 'lattices,'");
        assert_eq!(found[1], "a run of 2 white-space characters after 'lattices, Kronecker and'");
        assert!(whitespace_runs("one space between words, then an end ").is_empty());
        assert_eq!(whitespace_runs("a\ttab").len(), 1);
    }

    #[test]
    fn small_pictures_are_enlarged_to_the_minimum_width() {
        for w in [64, 80, 100, 128, 200, 256, 512] {
            assert!(w * picture_scale(w) >= MIN_PICTURE_WIDTH && (w * (picture_scale(w) - 1) < MIN_PICTURE_WIDTH));
        }
    }
}
