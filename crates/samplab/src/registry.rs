//! One registry core for everything samplab names: samplers, metrics, warps, integrands,
//! point-file formats, the renderer's built-in scenes and the report's papers.
//!
//! Every entry starts with the same [`About`] (name, aliases, one-line summary, typed
//! parameters with defaults and ranges, references) and adds what its kind needs (a
//! builder, counts and dimensions, flags). Each implementation file declares its own
//! entries beside its code; a kind's [`Registry`] is the list of those per-file tables,
//! one line per file. Lookup (case-insensitive, aliases, suggestions for unknown names),
//! spec resolution, help lists and `samplab list` are generated here, never hand-written.
//!
//! ```
//! use samplab::sampler::SAMPLERS;
//! let (entry, params) = SAMPLERS.resolve("GJittered:0.3").unwrap();
//! assert_eq!(entry.about.name, "jitter.gaussian");
//! assert_eq!(params.real("sigma"), 0.3);
//! assert!(SAMPLERS.lookup("sobl").unwrap_err().to_string().contains("did you mean sobol"));
//! ```

use std::fmt::Write as _;

use crate::error::{Error, Result, closest_names};
use crate::spec::{ParamSpec, Params, Spec};

/// What every registered entry says about itself.
#[derive(Debug, Clone, Copy)]
pub struct About {
    /// Canonical name (`family[.variant]`), lower case.
    pub name: &'static str,
    /// Other accepted names (the papers' own, common abbreviations), lower case.
    pub aliases: &'static [&'static str],
    /// One line: what it is or does.
    pub summary: &'static str,
    /// Parameters, in positional order.
    pub params: &'static [ParamSpec],
    /// Bibliography keys ([`crate::bibliography`]).
    pub references: &'static [&'static str],
    /// Whether the canonical spec leaves out the parameters at their defaults (the
    /// constructions named by their family alone: `net`, `lattice`, ...).
    pub terse: bool,
}

impl About {
    /// An entry with a name and a summary, and no aliases, parameters or references.
    pub const fn new(name: &'static str, summary: &'static str) -> About {
        About { name, aliases: &[], summary, params: &[], references: &[], terse: false }
    }

    /// The same, its canonical spec leaving out the parameters at their defaults.
    pub const fn terse(self) -> About {
        About { terse: true, ..self }
    }

    /// The same, with these aliases.
    pub const fn aliases(self, aliases: &'static [&'static str]) -> About {
        About { aliases, ..self }
    }

    /// The same, with these parameters.
    pub const fn params(self, params: &'static [ParamSpec]) -> About {
        About { params, ..self }
    }

    /// The same, with these references.
    pub const fn cite(self, references: &'static [&'static str]) -> About {
        About { references, ..self }
    }

    /// Whether `name` (lower case) is this entry's name or one of its aliases.
    fn answers_to(&self, name: &str) -> bool {
        self.name == name || self.aliases.contains(&name)
    }
}

/// A registered entry of some kind: its [`About`], and the lines `samplab list` prints
/// about it beyond the common ones.
pub trait Entry: Sync + 'static {
    /// The common description.
    fn about(&self) -> &About;

    /// Kind-specific lines for listings (counts, dimensions, flags), without indentation.
    fn details(&self) -> Vec<String> {
        Vec::new()
    }
}

/// The entries of one kind, gathered from the files that declare them.
#[derive(Debug)]
pub struct Registry<E: 'static> {
    kind: &'static str,
    heading: &'static str,
    /// Groups (a family folder's files), each a list of per-file tables.
    parts: &'static [&'static [&'static [E]]],
}

impl<E: Entry> Registry<E> {
    /// A registry of `kind` ("sampler", "metric", ...) whose listing starts with `heading`,
    /// made of the per-file tables `parts` in listing order, in groups (one per family
    /// folder; a registry of one folder has one group).
    pub const fn new(kind: &'static str, heading: &'static str, parts: &'static [&'static [&'static [E]]]) -> Self {
        Registry { kind, heading, parts }
    }

    /// What this registry holds ("sampler", "metric", ...).
    pub fn kind(&self) -> &'static str {
        self.kind
    }

    /// Every entry, in listing order.
    pub fn iter(&self) -> impl Iterator<Item = &'static E> + use<E> {
        self.parts.iter().flat_map(|g| g.iter()).flat_map(|p| p.iter())
    }

    /// The entry called `name` (canonical or alias, case-insensitive).
    ///
    /// # Errors
    /// [`Error::UnknownName`] with up to three close names as suggestions.
    pub fn lookup(&self, name: &str) -> Result<&'static E> {
        let want = name.trim().to_ascii_lowercase();
        self.iter().find(|e| e.about().answers_to(&want)).ok_or_else(|| Error::UnknownName {
            kind: self.kind,
            name: name.to_string(),
            suggestions: closest_names(
                name,
                self.iter().flat_map(|e| std::iter::once(e.about().name).chain(e.about().aliases.iter().copied())),
            ),
        })
    }

    /// The entry a spec (`name[:key=value,...]`) names, with its parameters resolved.
    ///
    /// # Errors
    /// A malformed spec, an unknown name, or unknown, repeated, malformed or out-of-range
    /// parameters ([`Error::Param`], naming the parameter and its valid range).
    pub fn resolve(&self, spec: &str) -> Result<(&'static E, Params)> {
        let spec = Spec::parse(spec)?;
        let entry = self.lookup(&spec.name)?;
        let params = Params::resolve(entry.about().name, entry.about().params, &spec.args)?;
        Ok((entry, params))
    }

    /// The canonical names, comma-separated (for help texts).
    pub fn names(&self) -> String {
        self.iter().map(|e| e.about().name).collect::<Vec<_>>().join(", ")
    }

    /// What is wrong with the declarations, one line per problem (empty when all is
    /// well): a name or alias registered twice or not in lower case, a reference missing
    /// from the bibliography, a parameter whose default does not match its kind or lies
    /// outside its range. The conformance tests call it on every registry.
    pub fn problems(&self) -> Vec<String> {
        let mut problems = Vec::new();
        let mut seen: Vec<&str> = Vec::new();
        for e in self.iter() {
            let a = e.about();
            for name in std::iter::once(a.name).chain(a.aliases.iter().copied()) {
                if seen.contains(&name) {
                    problems.push(format!("{} '{name}' is registered twice", self.kind));
                }
                if name != name.to_ascii_lowercase() || name.trim() != name || name.is_empty() {
                    problems.push(format!("{} '{name}': names are lower case, without spaces", self.kind));
                }
                seen.push(name);
            }
            for r in a.references {
                if crate::bibliography::lookup(r).is_none() {
                    problems.push(format!("{} '{}': unknown reference {r}", self.kind, a.name));
                }
            }
            for p in a.params {
                if let Err(why) = p.check() {
                    problems.push(format!("{} '{}': parameter '{}': {why}", self.kind, a.name, p.name));
                }
            }
        }
        problems
    }

    /// The listing `samplab list` prints: the heading, then per entry its name and summary,
    /// aliases, kind-specific details, parameters (default, range, meaning) and references.
    pub fn listing(&self) -> String {
        let mut out = format!("{}\n\n", self.heading);
        for e in self.iter() {
            let a = e.about();
            writeln!(out, "{}  —  {}", a.name, a.summary).expect("writing to a String");
            if !a.aliases.is_empty() {
                writeln!(out, "    aliases: {}", a.aliases.join(", ")).expect("writing to a String");
            }
            for line in e.details() {
                writeln!(out, "    {line}").expect("writing to a String");
            }
            for p in a.params {
                writeln!(out, "    {} = {}  ({}): {}", p.name, p.default_text(), p.range_text(), p.doc)
                    .expect("writing to a String");
            }
            if !a.references.is_empty() {
                writeln!(out, "    references: {}", a.references.join(", ")).expect("writing to a String");
            }
        }
        out
    }
}

/// Declare the files of one registry kind and the registry gathered from them: each file is
/// a module with a `pub(crate) static ENTRIES` table, so adding an entry is its file plus its
/// name in this list. A family folder declares its files the same way (`Family<Entry>`),
/// and the registry lists the families' `FILES`.
macro_rules! registry_files {
    (
        $(#[$doc:meta])*
        $vis:vis static $name:ident: Registry<$entry:ty> = ($kind:literal, $heading:literal) from [$($file:ident),+ $(,)?];
    ) => {
        $(pub mod $file;)+

        $(#[$doc])*
        $vis static $name: $crate::registry::Registry<$entry> =
            $crate::registry::Registry::new($kind, $heading, &[&[$($file::ENTRIES),+]]);
    };
    (
        $(#[$doc:meta])*
        $vis:vis static $name:ident: Family<$entry:ty> = [$($file:ident),+ $(,)?];
    ) => {
        $(pub mod $file;)+

        $(#[$doc])*
        $vis static $name: &[&[$entry]] = &[$($file::ENTRIES),+];
    };
}
pub(crate) use registry_files;

/// The canonical spec of an entry with resolved parameters: `name`, or
/// `name:key=value,...` with every parameter in declared order (a [`About::terse`] entry:
/// those not at their defaults).
pub fn canonical(about: &About, params: &Params) -> String {
    let shown = params.describe(|name| !about.terse || !params.is_default(about.params, name));
    if shown.is_empty() { about.name.to_string() } else { format!("{}:{shown}", about.name) }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spec::{Default, Kind};

    #[derive(Debug)]
    struct Thing(About);
    impl Entry for Thing {
        fn about(&self) -> &About {
            &self.0
        }
        fn details(&self) -> Vec<String> {
            vec!["detail".into()]
        }
    }

    const SIZE: &[ParamSpec] =
        &[ParamSpec { name: "size", kind: Kind::Int { min: 1, max: 9 }, default: Default::Int(3), doc: "how big" }];
    static A: &[Thing] = &[Thing(About::new("alpha", "first").aliases(&["a"]).params(SIZE).cite(&["cook1986"]))];
    static B: &[Thing] = &[Thing(About::new("beta.two", "second"))];
    static THINGS: Registry<Thing> = Registry::new("thing", "THINGS", &[&[A], &[B]]);

    #[test]
    fn looks_up_names_and_aliases_and_suggests() {
        assert_eq!(THINGS.lookup("ALPHA").unwrap().0.name, "alpha");
        assert_eq!(THINGS.lookup("a").unwrap().0.name, "alpha");
        assert_eq!(THINGS.lookup("beta.two").unwrap().0.name, "beta.two");
        let e = THINGS.lookup("alpah").unwrap_err().to_string();
        assert_eq!(e, "unknown thing 'alpah' (did you mean alpha?)");
        assert_eq!(THINGS.names(), "alpha, beta.two");
    }

    #[test]
    fn resolves_parameters_and_lists_everything() {
        let (e, p) = THINGS.resolve("a:size=5").unwrap();
        assert_eq!((e.0.name, p.int("size")), ("alpha", 5));
        assert_eq!(canonical(&e.0, &p), "alpha:size=5");
        assert!(THINGS.resolve("alpha:size=10").unwrap_err().to_string().contains("[1, 9]"));
        let list = THINGS.listing();
        for needle in
            ["THINGS", "alpha  —  first", "aliases: a", "detail", "size = 3", "references: cook1986", "beta.two"]
        {
            assert!(list.contains(needle), "{needle} missing from\n{list}");
        }
    }
}
