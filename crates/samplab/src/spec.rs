//! Method specs (`family[.variant][:key=value,...]`) and typed, range-checked parameters.
//!
//! Parameters may be given by name (`jitter.gaussian:sigma=0.25`) or by position in the
//! order the registry lists them (`jitter.gaussian:0.25`, `force-matrix:0.5,2`).

use crate::error::{Error, Result};

/// A spec split into its name and its raw arguments.
#[derive(Debug, Clone, PartialEq)]
pub struct Spec {
    /// The method name as written (case preserved, whitespace trimmed).
    pub name: String,
    /// `(Some(key), value)` for named arguments, `(None, value)` for positional ones.
    pub args: Vec<(Option<String>, String)>,
}

impl Spec {
    /// Split `text` at the first ':' and then at commas.
    ///
    /// # Errors
    /// An empty name or an empty argument.
    pub fn parse(text: &str) -> Result<Spec> {
        let (name, rest) = match text.split_once(':') {
            Some((n, r)) => (n.trim(), Some(r)),
            None => (text.trim(), None),
        };
        if name.is_empty() {
            return Err(Error::Parse { location: format!("spec '{text}'"), reason: "empty method name".into() });
        }
        let mut args = Vec::new();
        for part in rest.into_iter().flat_map(|r| r.split(',')) {
            let part = part.trim();
            if part.is_empty() {
                return Err(Error::Parse { location: format!("spec '{text}'"), reason: "empty parameter".into() });
            }
            args.push(match part.split_once('=') {
                Some((k, v)) => (Some(k.trim().to_ascii_lowercase()), v.trim().to_string()),
                None => (None, part.to_string()),
            });
        }
        Ok(Spec { name: name.to_string(), args })
    }
}

/// What values a parameter takes.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Kind {
    /// A real number in [min, max].
    Real {
        /// Smallest valid value.
        min: f64,
        /// Largest valid value.
        max: f64,
    },
    /// A whole number in [min, max].
    Int {
        /// Smallest valid value.
        min: u64,
        /// Largest valid value.
        max: u64,
    },
    /// One of a fixed list of words.
    Choice(&'static [&'static str]),
    /// A file's path (without commas: they separate parameters).
    Path,
    /// A list of real numbers, each in [min, max], separated by '/' (commas separate
    /// parameters).
    Reals {
        /// Smallest valid value.
        min: f64,
        /// Largest valid value.
        max: f64,
    },
}

/// The default of a parameter.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Default {
    /// A real number (for [`Kind::Real`]).
    Number(f64),
    /// A whole number (for [`Kind::Int`]).
    Int(u64),
    /// A word (for [`Kind::Choice`]).
    Word(&'static str),
    /// Chosen by the method from n and d; the text says how.
    Auto(&'static str),
}

/// One parameter of a registry entry.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ParamSpec {
    /// Its name in specs.
    pub name: &'static str,
    /// Valid values.
    pub kind: Kind,
    /// The value when not given.
    pub default: Default,
    /// One line: what it means, with its unit.
    pub doc: &'static str,
}

impl Kind {
    /// The kind's one-word name: `real`, `int`, `choice`, `path` or `reals`.
    pub fn name(&self) -> &'static str {
        match self {
            Kind::Real { .. } => "real",
            Kind::Int { .. } => "int",
            Kind::Choice(_) => "choice",
            Kind::Path => "path",
            Kind::Reals { .. } => "reals",
        }
    }
}

impl ParamSpec {
    /// The valid range or choices, in words.
    pub fn range_text(&self) -> String {
        match self.kind {
            Kind::Real { min, max } => format!("a number in [{min}, {max}]"),
            Kind::Int { min, max } => format!("a whole number in [{min}, {max}]"),
            Kind::Choice(c) => format!("one of {}", c.join(", ")),
            Kind::Path => "a file's path".into(),
            Kind::Reals { min, max } => format!("numbers in [{min}, {max}] separated by '/'"),
        }
    }

    /// Whether the declaration is consistent: the default has the parameter's kind and
    /// lies in its range (or is `Auto`), and a range is not empty.
    ///
    /// # Errors
    /// What is inconsistent, in words.
    pub fn check(&self) -> std::result::Result<(), String> {
        match (self.kind, self.default) {
            (_, Default::Auto(_)) => Ok(()),
            (Kind::Real { min, max }, Default::Number(x)) if min <= x && x <= max => Ok(()),
            (Kind::Int { min, max }, Default::Int(x)) if min <= x && x <= max => Ok(()),
            (Kind::Choice(c), Default::Word(w)) if c.contains(&w) => Ok(()),
            _ => Err(format!("default {} is not {}", self.default_text(), self.range_text())),
        }
    }

    /// The default, in words.
    pub fn default_text(&self) -> String {
        match self.default {
            Default::Number(x) => format!("{x}"),
            Default::Int(x) => format!("{x}"),
            Default::Word(w) => w.to_string(),
            Default::Auto(how) => format!("auto ({how})"),
        }
    }
}

/// A resolved parameter value.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Value {
    /// A real number ([`Kind::Real`]).
    Number(f64),
    /// A whole number ([`Kind::Int`]), exact over the whole u64 range.
    Int(u64),
    /// A word ([`Kind::Choice`]) or a path ([`Kind::Path`]).
    Word(String),
    /// Real numbers ([`Kind::Reals`]).
    Numbers(Vec<f64>),
    /// Left to the method.
    Auto,
}

/// Parameters resolved against a [`ParamSpec`] table: every declared name has a value.
#[derive(Debug, Clone, PartialEq)]
pub struct Params {
    values: Vec<(&'static str, Value)>,
}

impl Params {
    /// Resolve `args` for `owner` against `specs`.
    ///
    /// # Errors
    /// An unknown name, too many positional values, a repeated parameter, a value that
    /// does not parse, is not finite, or lies outside its range.
    pub fn resolve(owner: &str, specs: &[ParamSpec], args: &[(Option<String>, String)]) -> Result<Params> {
        let mut given: Vec<Option<&str>> = vec![None; specs.len()];
        for (pos, (key, raw)) in args.iter().enumerate() {
            let idx = match key {
                Some(k) => specs.iter().position(|s| s.name == k).ok_or_else(|| Error::Param {
                    owner: owner.into(),
                    param: k.clone(),
                    reason: if specs.is_empty() {
                        "this method takes no parameters".into()
                    } else {
                        format!("unknown; valid: {}", specs.iter().map(|s| s.name).collect::<Vec<_>>().join(", "))
                    },
                })?,
                None if pos < specs.len() => pos,
                None => {
                    return Err(Error::Param {
                        owner: owner.into(),
                        param: format!("#{}", pos + 1),
                        reason: format!(
                            "'{raw}' is one value too many: this method takes {} parameter(s)",
                            specs.len()
                        ),
                    });
                }
            };
            if given[idx].replace(raw).is_some() {
                return Err(Error::Param {
                    owner: owner.into(),
                    param: specs[idx].name.into(),
                    reason: "given twice".into(),
                });
            }
        }
        let values = specs
            .iter()
            .zip(given)
            .map(|(spec, raw)| Ok((spec.name, parse_value(owner, spec, raw)?)))
            .collect::<Result<_>>()?;
        Ok(Params { values })
    }

    fn get(&self, name: &str) -> &Value {
        &self.values.iter().find(|(n, _)| *n == name).unwrap_or_else(|| panic!("parameter '{name}' is not declared")).1
    }

    /// The real number `name` holds, or None when it is left to the method (`auto`).
    ///
    /// # Panics
    /// When `name` is not a declared real parameter (a programming error that the
    /// registries' conformance tests catch).
    pub fn real_or_auto(&self, name: &str) -> Option<f64> {
        match self.get(name) {
            Value::Number(x) => Some(*x),
            Value::Auto => None,
            v => panic!("parameter '{name}' is not a real number: {v:?}"),
        }
    }

    /// The real number `name` holds.
    ///
    /// # Panics
    /// As [`Params::real_or_auto`], and when the parameter is `auto`.
    pub fn real(&self, name: &str) -> f64 {
        self.real_or_auto(name).unwrap_or_else(|| panic!("parameter '{name}' has no value"))
    }

    /// The whole number `name` holds, or None when it is left to the method (`auto`).
    ///
    /// # Panics
    /// When `name` is not a declared whole-number parameter.
    pub fn int_or_auto(&self, name: &str) -> Option<u64> {
        match self.get(name) {
            Value::Int(x) => Some(*x),
            Value::Auto => None,
            v => panic!("parameter '{name}' is not a whole number: {v:?}"),
        }
    }

    /// The whole number `name` holds.
    ///
    /// # Panics
    /// As [`Params::int_or_auto`], and when the parameter is `auto`.
    pub fn int(&self, name: &str) -> u64 {
        self.int_or_auto(name).unwrap_or_else(|| panic!("parameter '{name}' has no value"))
    }

    /// The word `name` holds.
    ///
    /// # Panics
    /// When `name` is not a declared word parameter.
    pub fn word(&self, name: &str) -> &str {
        match self.get(name) {
            Value::Word(w) => w,
            v => panic!("parameter '{name}' is not a word: {v:?}"),
        }
    }

    /// The path `name` holds, or None when it is left to the method (`auto`).
    ///
    /// # Panics
    /// When `name` is not a declared path parameter.
    pub fn path_or_auto(&self, name: &str) -> Option<&str> {
        match self.get(name) {
            Value::Word(w) => Some(w),
            Value::Auto => None,
            v => panic!("parameter '{name}' is not a path: {v:?}"),
        }
    }

    /// The paths held by the parameters that `specs` declares as [`Kind::Path`] (those not
    /// left to the method): the files a spec reads.
    pub fn paths(&self, specs: &[ParamSpec]) -> Vec<std::path::PathBuf> {
        specs
            .iter()
            .filter(|s| matches!(s.kind, Kind::Path))
            .filter_map(|s| self.path_or_auto(s.name))
            .map(std::path::PathBuf::from)
            .collect()
    }

    /// The real numbers `name` holds, or None when they are left to the method (`auto`).
    ///
    /// # Panics
    /// When `name` is not a declared list parameter.
    pub fn reals_or_auto(&self, name: &str) -> Option<&[f64]> {
        match self.get(name) {
            Value::Numbers(x) => Some(x),
            Value::Auto => None,
            v => panic!("parameter '{name}' is not a list of numbers: {v:?}"),
        }
    }

    /// The value `name` holds is its declared default (`specs` the declarations).
    pub fn is_default(&self, specs: &[ParamSpec], name: &str) -> bool {
        let Some(spec) = specs.iter().find(|s| s.name == name) else {
            return false;
        };
        match (self.get(name), spec.default) {
            (Value::Number(x), Default::Number(d)) => *x == d,
            (Value::Int(x), Default::Int(d)) => *x == d,
            (Value::Word(w), Default::Word(d)) => w == d,
            (Value::Auto, Default::Auto(_)) => true,
            _ => false,
        }
    }

    /// Set `name` to `value`: a method that resolves an `auto` parameter records what it
    /// chose, so that its spec names it.
    ///
    /// # Panics
    /// When `name` is not declared (a programming error).
    pub fn set(&mut self, name: &str, value: Value) {
        let slot = self.values.iter_mut().find(|(n, _)| *n == name);
        slot.unwrap_or_else(|| panic!("parameter '{name}' is not declared")).1 = value;
    }

    /// `name=value` pairs of the parameters `shown` keeps, for specs, headers and logs.
    pub fn describe(&self, shown: impl Fn(&str) -> bool) -> String {
        self.values
            .iter()
            .filter(|(n, _)| shown(n))
            .map(|(n, v)| match v {
                Value::Number(x) => format!("{n}={x}"),
                Value::Int(x) => format!("{n}={x}"),
                Value::Word(w) => format!("{n}={w}"),
                Value::Numbers(x) => {
                    format!("{n}={}", x.iter().map(f64::to_string).collect::<Vec<_>>().join("/"))
                }
                Value::Auto => format!("{n}=auto"),
            })
            .collect::<Vec<_>>()
            .join(",")
    }
}

fn parse_value(owner: &str, spec: &ParamSpec, raw: Option<&str>) -> Result<Value> {
    let bad = |reason: String| Error::Param { owner: owner.into(), param: spec.name.into(), reason };
    let Some(raw) = raw else {
        return Ok(match spec.default {
            Default::Number(x) => Value::Number(x),
            Default::Int(x) => Value::Int(x),
            Default::Word(w) => Value::Word(w.into()),
            Default::Auto(_) => Value::Auto,
        });
    };
    if raw.eq_ignore_ascii_case("auto") && matches!(spec.default, Default::Auto(_)) {
        return Ok(Value::Auto);
    }
    match spec.kind {
        Kind::Choice(choices) => choices
            .iter()
            .find(|c| c.eq_ignore_ascii_case(raw))
            .map(|c| Value::Word((*c).into()))
            .ok_or_else(|| bad(format!("'{raw}' is not {}", spec.range_text()))),
        Kind::Path => Ok(Value::Word(raw.into())),
        Kind::Real { min, max } => Ok(Value::Number(parse_real(raw, min, max, spec, &bad)?)),
        Kind::Reals { min, max } => Ok(Value::Numbers(
            raw.split('/').map(|x| parse_real(x.trim(), min, max, spec, &bad)).collect::<Result<_>>()?,
        )),
        Kind::Int { min, max } => {
            let x: u64 = raw
                .parse()
                .map_err(|_| bad(format!("'{raw}' is not a whole number; expected {}", spec.range_text())))?;
            if x < min || x > max {
                return Err(bad(format!("{raw} is out of range; expected {}", spec.range_text())));
            }
            Ok(Value::Int(x))
        }
    }
}

/// One finite number in [min, max].
fn parse_real(raw: &str, min: f64, max: f64, spec: &ParamSpec, bad: &dyn Fn(String) -> Error) -> Result<f64> {
    let x: f64 = raw.parse().map_err(|_| bad(format!("'{raw}' is not a number; expected {}", spec.range_text())))?;
    if !x.is_finite() || x < min || x > max {
        return Err(bad(format!("{raw} is out of range; expected {}", spec.range_text())));
    }
    Ok(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    const SPECS: &[ParamSpec] = &[
        ParamSpec { name: "sigma", kind: Kind::Real { min: 0.0, max: 4.0 }, default: Default::Number(0.25), doc: "" },
        ParamSpec { name: "edge", kind: Kind::Choice(&["wrap", "resample"]), default: Default::Word("wrap"), doc: "" },
    ];

    #[test]
    fn parses_named_and_positional() {
        let s = Spec::parse("jitter.gaussian:sigma=0.5").unwrap();
        assert_eq!(s.name, "jitter.gaussian");
        let p = Params::resolve("g", SPECS, &s.args).unwrap();
        assert_eq!(p.real("sigma"), 0.5);
        assert_eq!(p.word("edge"), "wrap");
        let s = Spec::parse("g:0.1,resample").unwrap();
        let p = Params::resolve("g", SPECS, &s.args).unwrap();
        assert_eq!(p.real("sigma"), 0.1);
        assert_eq!(p.word("edge"), "resample");
    }

    #[test]
    fn whole_numbers_stay_exact_over_u64() {
        // 2^53 + 1 is the first integer an f64 cannot hold: a parameter stored as f64 would
        // silently become 2^53
        const SEED: &[ParamSpec] =
            &[ParamSpec { name: "seed", kind: Kind::Int { min: 0, max: u64::MAX }, default: Default::Int(0), doc: "" }];
        for raw in ["9007199254740993", "18446744073709551615"] {
            let p = Params::resolve("g", SEED, &Spec::parse(&format!("g:seed={raw}")).unwrap().args).unwrap();
            assert_eq!(p.int("seed").to_string(), raw);
            assert_eq!(p.describe(|_| true), format!("seed={raw}"));
        }
        let e = Params::resolve("g", SEED, &Spec::parse("g:seed=18446744073709551616").unwrap().args).unwrap_err();
        assert!(e.to_string().contains("'seed'"), "{e}");
    }

    #[test]
    fn rejects_bad_parameters_with_their_name_and_range() {
        let run = |t: &str| Params::resolve("g", SPECS, &Spec::parse(t).unwrap().args).unwrap_err().to_string();
        assert!(run("g:sigma=9").contains("'sigma'") && run("g:sigma=9").contains("[0, 4]"));
        assert!(run("g:sigma=nan").contains("out of range"));
        assert!(run("g:sigma=abc").contains("not a number"));
        assert!(run("g:width=1").contains("valid: sigma, edge"));
        assert!(run("g:1,wrap,3").contains("one value too many"));
        assert!(run("g:0.1,sigma=0.2").contains("given twice"));
        assert!(run("g:edge=clamp").contains("one of wrap, resample"));
        assert!(Spec::parse(":x").is_err());
        assert!(Spec::parse("g:1,,2").is_err());
    }
}
