//! The coverage table: every numbered table and figure of a paper (and each numbered
//! equation or closed form it states as a result), in the paper's own numbering, with what
//! samplab does with it. The list lives in `data/published.json` beside the published
//! numbers; the status of each item is computed from the verdicts of the claims it lists,
//! never written by hand, so the table cannot say more than the run shows.

use serde::Deserialize;

use crate::{Claim, Error, Verdict};

/// One numbered item of a paper.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Item {
    /// The paper's numbering ("Table 5", "Figure 3", "Eq. 10").
    pub item: String,
    /// What it is, in a few words.
    pub what: String,
    /// The experiment of the report that reproduces it.
    #[serde(default)]
    pub experiment: Option<String>,
    /// The claims (ids) that test it.
    #[serde(default)]
    pub claims: Vec<String>,
    /// The figures and tables (ids) of the report that show it.
    #[serde(default)]
    pub shows: Vec<String>,
    /// Why it is not attempted (then there is no experiment).
    #[serde(default)]
    pub not_attempted: Option<String>,
    /// The figure of `shows` that the index opens the paper's overview with (one or two
    /// items per paper carry one).
    #[serde(default)]
    pub key: Option<String>,
}

/// The status of an item, from its claims' verdicts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Status {
    /// Every claim reproduced.
    Reproduced,
    /// Some claim not reproduced, each such claim with a written explanation.
    Differs,
    /// Some claim not reproduced without an explanation.
    NotReproduced,
    /// No claim contradicted, some undecided.
    Undecided,
    /// Every claim derived (an identity, algebra, a closed form or a deterministic sampler
    /// at fixed positions: no random measurement), and each holds: checked, not a
    /// reproduction of a result.
    Checked,
    /// No measured claim fails, and a derived claim does: the paper's statement is
    /// contradicted by algebra or an exact computation.
    Contradicted,
    /// Drawn or computed in the report; the paper states nothing about it to test.
    Shown,
    /// Not in the report; the item says why.
    NotAttempted,
}

impl Status {
    /// Every status, in the order the tables list them.
    pub const ALL: [Status; 8] = [
        Status::Reproduced,
        Status::Differs,
        Status::NotReproduced,
        Status::Undecided,
        Status::Checked,
        Status::Contradicted,
        Status::Shown,
        Status::NotAttempted,
    ];

    /// Its name in the report (also the CSS class).
    pub fn name(self) -> &'static str {
        match self {
            Status::Reproduced => "reproduced",
            Status::Differs => "differs",
            Status::NotReproduced => "not reproduced",
            Status::Undecided => "undecided",
            Status::Checked => "checked",
            Status::Contradicted => "contradicted",
            Status::Shown => "shown",
            Status::NotAttempted => "not attempted",
        }
    }
}

/// The coverage list of paper `key`.
///
/// # Panics
/// The data file's entry is missing or malformed: a programming error, caught by the
/// report tests.
pub fn items(key: &str) -> Vec<Item> {
    let v = &crate::published::data()[key]["coverage"];
    serde_json::from_value(v.clone()).unwrap_or_else(|e| panic!("published.json {key}.coverage: {e}"))
}

/// The status of `item` given the run's claims of its paper.
pub fn status(item: &Item, claims: &[&Claim]) -> Status {
    if item.not_attempted.is_some() {
        return Status::NotAttempted;
    }
    let mine: Vec<&&Claim> = claims.iter().filter(|c| item.claims.contains(&c.id)).collect();
    if mine.is_empty() {
        return Status::Shown;
    }
    let failed: Vec<&&&Claim> = mine.iter().filter(|c| c.verdict() == Verdict::NotReproduced).collect();
    if !failed.is_empty() {
        return if failed.iter().all(|c| c.derived) {
            Status::Contradicted
        } else if failed.iter().all(|c| c.explanation.is_some()) {
            Status::Differs
        } else {
            Status::NotReproduced
        };
    }
    if mine.iter().any(|c| c.verdict() == Verdict::Undecided) {
        Status::Undecided
    } else if mine.iter().all(|c| c.derived) {
        Status::Checked
    } else {
        Status::Reproduced
    }
}

/// The coverage audit: what a row's status promises, checked against the report. Every
/// attempted row links to at least one figure or table that the run made (`made`: their
/// ids), and a row that is reproduced or differs rests on at least one measured claim (not
/// derived). Returns every breach, naming the row.
pub fn audit(items: &[Item], claims: &[&Claim], made: &[&str]) -> Vec<String> {
    let mut breaches = Vec::new();
    for it in items {
        let status = status(it, claims);
        if status == Status::NotAttempted {
            continue;
        }
        if it.shows.is_empty() {
            breaches.push(format!("{}: {} but shows no figure or table", it.item, status.name()));
        }
        for id in &it.shows {
            if !made.contains(&id.as_str()) {
                breaches.push(format!("{}: shows {id}, which the run did not make", it.item));
            }
        }
        if let Some(key) = &it.key
            && !it.shows.contains(key)
        {
            breaches.push(format!("{}: its key figure {key} is not one it shows", it.item));
        }
        let tested = claims.iter().any(|c| it.claims.contains(&c.id) && !c.derived);
        if matches!(status, Status::Reproduced | Status::Differs) && !tested {
            breaches.push(format!("{}: {} on derived claims alone", it.item, status.name()));
        }
    }
    breaches
}

/// Check that the coverage list of a paper and its claims fit: each item either names an
/// experiment of the paper or says why it is not attempted; each claim is listed by an
/// item; each listed claim exists; claim ids are unique.
///
/// # Errors
/// The first mismatch, naming it.
pub fn check(key: &str, items: &[Item], experiments: &[&str], claims: &[&Claim]) -> Result<(), Error> {
    let bad = |m: String| Err(Error::Coverage { paper: key.into(), reason: format!("published.json: {m}") });
    for it in items {
        match (&it.experiment, &it.not_attempted) {
            (Some(e), None) if experiments.contains(&e.as_str()) => {}
            (Some(e), None) => return bad(format!("{}: no experiment {e}", it.item)),
            (None, Some(_)) if it.claims.is_empty() => {}
            _ => return bad(format!("{}: needs an experiment or a reason it is not attempted", it.item)),
        }
        for c in &it.claims {
            if !claims.iter().any(|x| &x.id == c) {
                return bad(format!("{}: no claim {c} in the run", it.item));
            }
        }
    }
    for (i, c) in claims.iter().enumerate() {
        if claims[..i].iter().any(|x| x.id == c.id) {
            return bad(format!("claim {} appears twice", c.id));
        }
        if !items.iter().any(|it| it.claims.contains(&c.id)) {
            return bad(format!("claim {} is listed by no item", c.id));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::criteria::{Decision, exactly};

    fn claim(id: &str, d: Decision, explained: bool) -> Claim {
        Claim { id: id.into(), decision: d, explanation: explained.then(|| "why".into()), ..Claim::default() }
    }

    fn item(claims: &[&str]) -> Item {
        Item {
            item: "Table 1".into(),
            what: "x".into(),
            experiment: Some("e".into()),
            claims: claims.iter().map(|s| s.to_string()).collect(),
            shows: vec!["fig".into()],
            not_attempted: None,
            key: None,
        }
    }

    #[test]
    fn the_status_is_the_worst_claim() {
        let ok = claim("a", exactly(true, ""), false);
        let bad = claim("b", exactly(false, ""), false);
        let explained = claim("c", exactly(false, ""), true);
        let open = claim("d", Decision::default(), false);
        let all = [&ok, &bad, &explained, &open];
        assert_eq!(status(&item(&["a"]), &all), Status::Reproduced);
        assert_eq!(status(&item(&["a", "b"]), &all), Status::NotReproduced);
        assert_eq!(status(&item(&["a", "c"]), &all), Status::Differs);
        assert_eq!(status(&item(&["b", "c"]), &all), Status::NotReproduced);
        assert_eq!(status(&item(&["a", "d"]), &all), Status::Undecided);
        assert_eq!(status(&item(&["c", "d"]), &all), Status::Differs);
        assert_eq!(status(&item(&[]), &all), Status::Shown);
        let derived = Claim { derived: true, ..claim("i", exactly(true, ""), false) };
        let wrong = Claim { derived: true, ..claim("w", exactly(false, ""), true) };
        let all = [&ok, &derived, &wrong, &bad, &explained];
        assert_eq!(status(&item(&["i"]), &all), Status::Checked);
        assert_eq!(status(&item(&["a", "i"]), &all), Status::Reproduced);
        // a derived claim that fails contradicts the paper; a measured failure beside it
        // still decides the row
        assert_eq!(status(&item(&["a", "i", "w"]), &all), Status::Contradicted);
        assert_eq!(status(&item(&["w", "b"]), &all), Status::NotReproduced);
        assert_eq!(status(&item(&["w", "c"]), &all), Status::Differs);
    }

    /// Every verdict a claim can show is one the report counts, once.
    #[test]
    fn every_verdict_shown_is_counted() {
        let mut claims = Vec::new();
        for derived in [false, true] {
            for verdict in [Verdict::Reproduced, Verdict::NotReproduced, Verdict::Undecided] {
                let decision = Decision { verdict, criterion: String::new() };
                claims.push(Claim { derived, ..claim("x", decision, false) });
            }
        }
        // reproduced, not reproduced, undecided; checked, contradicted, undecided
        assert_eq!(crate::tally(&claims), [1, 1, 1, 1, 2]);
    }

    #[test]
    fn the_audit_refuses_a_status_without_a_figure_and_derived_claims_never_reproduce() {
        let ok = claim("a", exactly(true, ""), false);
        let derived = Claim { derived: true, ..claim("i", exactly(true, ""), false) };
        let contradicted = Claim { derived: true, ..claim("f", exactly(false, ""), true) };
        let measured_failure = claim("m", exactly(false, ""), true);
        let reproduced_on_derived = Claim { derived: true, ..claim("r", exactly(true, ""), false) };
        let all = [&ok, &derived, &contradicted, &measured_failure, &reproduced_on_derived];
        assert!(audit(&[item(&["a"])], &all, &["fig"]).is_empty());
        // a figure the run did not make, and no figure at all
        assert!(audit(&[item(&["a"])], &all, &["other"])[0].contains("did not make"));
        let bare = Item { shows: Vec::new(), ..item(&[]) };
        assert!(audit(&[bare], &all, &["fig"])[0].contains("shown but shows no figure"));
        // derived claims alone give "checked" or "contradicted", which is what they say; a
        // row that differs needs a measured claim
        assert!(audit(&[item(&["i"])], &all, &["fig"]).is_empty(), "checked on a derived claim is what it says");
        assert!(audit(&[item(&["f"])], &all, &["fig"]).is_empty(), "contradicted by a derivation is what it says");
        assert!(audit(&[item(&["m", "i"])], &all, &["fig"]).is_empty());
        assert_eq!(status(&item(&["i", "r"]), &all), Status::Checked, "never reproduced on derived claims alone");
        // a key figure must be one the item shows
        let keyed = |key: &str| Item { key: Some(key.into()), ..item(&["a"]) };
        assert!(audit(&[keyed("fig")], &all, &["fig"]).is_empty());
        assert!(audit(&[keyed("other")], &all, &["fig", "other"])[0].contains("key figure other is not one it shows"));
    }

    #[test]
    fn check_finds_unlisted_and_missing_claims() {
        let a = claim("a", exactly(true, ""), false);
        assert!(check("p", &[item(&["a"])], &["e"], &[&a]).is_ok());
        assert!(check("p", &[item(&[])], &["e"], &[&a]).unwrap_err().to_string().contains("listed by no item"));
        assert!(check("p", &[item(&["a", "z"])], &["e"], &[&a]).unwrap_err().to_string().contains("no claim z"));
        assert!(check("p", &[item(&["a"])], &["f"], &[&a]).unwrap_err().to_string().contains("no experiment e"));
        assert!(check("p", &[item(&["a"])], &["e"], &[&a, &a]).unwrap_err().to_string().contains("twice"));
    }

    #[test]
    fn every_paper_has_a_well_formed_list() {
        for p in crate::paper::all() {
            let items = items(p.key);
            assert!(!items.is_empty(), "{}: no coverage", p.key);
            let ids: Vec<&str> = p.experiments.iter().map(|e| e.id).collect();
            for it in &items {
                match (&it.experiment, &it.not_attempted) {
                    (Some(e), None) => assert!(ids.contains(&e.as_str()), "{}: {}: no experiment {e}", p.key, it.item),
                    (None, Some(why)) => assert!(why.len() > 20 && it.claims.is_empty(), "{}: {}", p.key, it.item),
                    _ => panic!("{}: {}: an experiment or a reason", p.key, it.item),
                }
            }
        }
    }
}
