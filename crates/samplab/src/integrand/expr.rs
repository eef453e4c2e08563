//! An integrand written as a formula in x0 .. x(d-1), such as `exp(-x0*x0 - x1*x1)`:
//! parsed once into a tape of operations, then evaluated a block of points at a time (each
//! operation runs over the whole block, so the interpreter's dispatch is paid once per
//! block, not once per point). Nothing is ever run as code: the grammar below is all there
//! is.
//!
//! ```text
//! sum     := product (('+' | '-') product)*
//! product := unary (('*' | '/') unary)*
//! unary   := ('-' | '+') unary | power
//! power   := atom (('^' | '**') unary)?          right-associative; -x^2 is -(x^2)
//! atom    := number | x<k> | pi | e | name '(' sum (',' sum)* ')' | '(' sum ')'
//! ```
//!
//! Functions of one argument: exp, log (natural), sqrt, sin, cos, tan, asin, acos, atan,
//! sinh, cosh, tanh, abs, floor, ceil, step (1 where its argument is at least 0, else 0);
//! of two: min, max, pow, atan2.

use super::Integrand;
use crate::error::{Error, Result};

/// Points evaluated together.
const BLOCK: usize = 256;

/// A function of one argument.
type Unary = fn(f64) -> f64;
/// A function of two arguments.
type Binary = fn(f64, f64) -> f64;

/// Functions of one argument, by name.
const UNARY: &[(&str, Unary)] = &[
    ("exp", f64::exp),
    ("log", f64::ln),
    ("sqrt", f64::sqrt),
    ("sin", f64::sin),
    ("cos", f64::cos),
    ("tan", f64::tan),
    ("asin", f64::asin),
    ("acos", f64::acos),
    ("atan", f64::atan),
    ("sinh", f64::sinh),
    ("cosh", f64::cosh),
    ("tanh", f64::tanh),
    ("abs", f64::abs),
    ("floor", f64::floor),
    ("ceil", f64::ceil),
    ("step", |t| if t >= 0.0 { 1.0 } else { 0.0 }),
];

/// Functions of two arguments, by name.
const BINARY: &[(&str, Binary)] = &[("min", f64::min), ("max", f64::max), ("pow", f64::powf), ("atan2", f64::atan2)];

/// One operation of the tape: operands name the earlier operations whose values they take
/// (used while parsing, to fold constants). The tape is in postorder, every operation's
/// operands the values computed just before it, so it is evaluated on a stack.
#[derive(Debug, Clone, Copy)]
enum Op {
    Var(usize),
    Const(f64),
    Neg(usize),
    Add(usize, usize),
    Sub(usize, usize),
    Mul(usize, usize),
    Div(usize, usize),
    Unary(Unary, usize),
    Binary(Binary, usize, usize),
}

impl Op {
    /// The value of this operation on scalar operands (for folding constants).
    fn scalar(self, slot: impl Fn(usize) -> f64) -> f64 {
        match self {
            Op::Var(_) => unreachable!("a variable is not constant"),
            Op::Const(c) => c,
            Op::Neg(a) => -slot(a),
            Op::Add(a, b) => slot(a) + slot(b),
            Op::Sub(a, b) => slot(a) - slot(b),
            Op::Mul(a, b) => slot(a) * slot(b),
            Op::Div(a, b) => slot(a) / slot(b),
            Op::Unary(f, a) => f(slot(a)),
            Op::Binary(f, a, b) => f(slot(a), slot(b)),
        }
    }

    fn operands(self) -> [Option<usize>; 2] {
        match self {
            Op::Var(_) | Op::Const(_) => [None, None],
            Op::Neg(a) | Op::Unary(_, a) => [Some(a), None],
            Op::Add(a, b) | Op::Sub(a, b) | Op::Mul(a, b) | Op::Div(a, b) | Op::Binary(_, a, b) => [Some(a), Some(b)],
        }
    }

    /// How many values it takes from the stack (it leaves one).
    fn arity(self) -> usize {
        self.operands().iter().flatten().count()
    }
}

/// How deep parentheses, signs, powers and function calls may nest: the parser recurses
/// once per level, and a formula nested 10^5 deep overflowed the stack (an abort, not an
/// error).
pub const MAX_NESTING: usize = 256;

/// An integrand given as a formula; its exact integral is unknown unless the caller states
/// it ([`Expr::with_exact`]).
///
/// ```
/// use samplab::integrand::{Expr, Integrand};
/// let f = Expr::parse("exp(-x0*x0 - x1*x1)", None).unwrap();
/// assert_eq!(f.dims(), 2);
/// assert!((f.eval(&[0.5, 0.25]) - (-0.3125f64).exp()).abs() < 1e-15);
/// let err = Expr::parse("exp(-x0*x0 - )", None).unwrap_err();
/// assert!(err.to_string().contains("column 14"));
/// ```
#[derive(Debug, Clone)]
pub struct Expr {
    text: String,
    tape: Vec<Op>,
    /// The most values on the stack at once.
    height: usize,
    dims: usize,
    exact: f64,
}

/// Variables x0 .. x65535: more dimensions than any integrand is sampled in.
const MAX_VARIABLES: usize = 1 << 16;

impl Expr {
    /// Parse `text`. Its dimensions are `dims` where given (every variable must be below
    /// it), otherwise one more than the highest variable's index.
    ///
    /// # Errors
    /// [`Error::Parse`] naming the column of the first thing that is wrong; a variable at
    /// or above `dims`.
    pub fn parse(text: &str, dims: Option<usize>) -> Result<Expr> {
        let tokens = tokenize(text)?;
        let mut parser = Parser { text, tokens: &tokens, at: 0, tape: Vec::new(), depth: 0 };
        parser.sum()?;
        if let Some(token) = tokens.get(parser.at) {
            return Err(parser.error(token.column, &format!("unexpected {}", token.kind.describe())));
        }
        let used = parser.tape.iter().filter_map(|op| if let Op::Var(k) = op { Some(k + 1) } else { None }).max();
        let dims = match (dims, used) {
            (Some(d), Some(u)) if u > d => {
                return Err(Error::Parse {
                    location: format!("expression `{text}`"),
                    reason: format!("it uses x{} but the integrand has {d} dimensions (x0 .. x{})", u - 1, d - 1),
                });
            }
            (Some(0), _) => {
                return Err(Error::Setting { name: "dims", value: "0".into(), reason: "must be at least 1".into() });
            }
            (Some(d), _) => d,
            (None, u) => u.unwrap_or(1),
        };
        let height = parser
            .tape
            .iter()
            .scan(0, |h, op| {
                *h = *h + 1 - op.arity();
                Some(*h)
            })
            .max()
            .unwrap_or(1);
        Ok(Expr { text: text.to_string(), tape: parser.tape, height, dims, exact: f64::NAN })
    }

    /// The same integrand with its exact integral stated.
    #[must_use]
    pub fn with_exact(mut self, exact: f64) -> Expr {
        self.exact = exact;
        self
    }

    /// The text it was parsed from.
    pub fn text(&self) -> &str {
        &self.text
    }

    /// Values of one block of at most [`BLOCK`] points into `out`, `stack` as scratch:
    /// each operation replaces its operands on the stack by its value.
    fn block(&self, points: &[f64], out: &mut [f64], stack: &mut [[f64; BLOCK]]) {
        let m = out.len();
        let mut h = 0;
        for op in &self.tape {
            let (below, top) = stack.split_at_mut(h);
            match *op {
                Op::Var(k) => {
                    for (v, x) in top[0][..m].iter_mut().zip(points.chunks_exact(self.dims)) {
                        *v = x[k];
                    }
                }
                Op::Const(c) => top[0][..m].fill(c),
                Op::Neg(_) => below[h - 1][..m].iter_mut().for_each(|v| *v = -*v),
                Op::Unary(f, _) => below[h - 1][..m].iter_mut().for_each(|v| *v = f(*v)),
                Op::Add(..) | Op::Sub(..) | Op::Mul(..) | Op::Div(..) | Op::Binary(..) => {
                    let (a, b) = below.split_at_mut(h - 1);
                    let pairs = a[h - 2][..m].iter_mut().zip(&b[0][..m]);
                    match *op {
                        Op::Add(..) => pairs.for_each(|(a, b)| *a += b),
                        Op::Sub(..) => pairs.for_each(|(a, b)| *a -= b),
                        Op::Mul(..) => pairs.for_each(|(a, b)| *a *= b),
                        Op::Div(..) => pairs.for_each(|(a, b)| *a /= b),
                        Op::Binary(f, ..) => pairs.for_each(|(a, b)| *a = f(*a, *b)),
                        _ => unreachable!("a binary operation"),
                    }
                }
            }
            h = h + 1 - op.arity();
        }
        out.copy_from_slice(&stack[0][..m]);
    }
}

impl Integrand for Expr {
    fn dims(&self) -> usize {
        self.dims
    }
    fn eval(&self, x: &[f64]) -> f64 {
        let mut out = [0.0];
        self.eval_many(&x[..self.dims], &mut out);
        out[0]
    }
    fn eval_many(&self, points: &[f64], out: &mut [f64]) {
        let mut stack = vec![[0.0; BLOCK]; self.height];
        for (p, o) in points.chunks(BLOCK * self.dims).zip(out.chunks_mut(BLOCK)) {
            self.block(p, o, &mut stack);
        }
    }
    fn exact(&self) -> f64 {
        self.exact
    }
}

#[derive(Debug, Clone, PartialEq)]
enum TokenKind {
    Number(f64),
    Name(String),
    Symbol(&'static str),
}

impl TokenKind {
    fn describe(&self) -> String {
        match self {
            TokenKind::Number(x) => format!("number {x}"),
            TokenKind::Name(name) => format!("`{name}`"),
            TokenKind::Symbol(s) => format!("`{s}`"),
        }
    }
}

#[derive(Debug)]
struct Token {
    kind: TokenKind,
    /// 1-based, in characters.
    column: usize,
}

/// Where an error is: the expression and the column, the expression cut to the
/// [`SHOWN`] characters either side of the column when longer.
fn at_column(text: &str, column: usize) -> String {
    let chars: Vec<char> = text.chars().collect();
    if chars.len() <= 2 * SHOWN {
        return format!("expression `{text}` column {column}");
    }
    let (from, to) = (column.saturating_sub(SHOWN + 1), (column + SHOWN).min(chars.len()));
    let cut = |on: bool| if on { "..." } else { "" };
    let excerpt: String = chars[from..to].iter().collect();
    format!(
        "expression `{}{excerpt}{}` ({} characters) column {column}",
        cut(from > 0),
        cut(to < chars.len()),
        chars.len()
    )
}

/// Characters shown either side of an error's column in a long expression.
const SHOWN: usize = 40;

fn tokenize(text: &str) -> Result<Vec<Token>> {
    let chars: Vec<char> = text.chars().collect();
    let mut tokens = Vec::new();
    let mut i = 0;
    let fail = |column: usize, reason: String| Error::Parse { location: at_column(text, column), reason };
    while i < chars.len() {
        let c = chars[i];
        let column = i + 1;
        if c.is_whitespace() {
            i += 1;
        } else if c.is_ascii_digit() || (c == '.' && chars.get(i + 1).is_some_and(char::is_ascii_digit)) {
            let start = i;
            while i < chars.len() && (chars[i].is_ascii_digit() || chars[i] == '.') {
                i += 1;
            }
            if i < chars.len() && (chars[i] == 'e' || chars[i] == 'E') {
                let sign = usize::from(matches!(chars.get(i + 1), Some('+' | '-')));
                if chars.get(i + 1 + sign).is_some_and(char::is_ascii_digit) {
                    i += 1 + sign;
                    while i < chars.len() && chars[i].is_ascii_digit() {
                        i += 1;
                    }
                }
            }
            let word: String = chars[start..i].iter().collect();
            let value = word.parse::<f64>().map_err(|_| fail(column, format!("`{word}` is not a number")))?;
            tokens.push(Token { kind: TokenKind::Number(value), column });
        } else if c.is_ascii_alphabetic() || c == '_' {
            let start = i;
            while i < chars.len() && (chars[i].is_ascii_alphanumeric() || chars[i] == '_') {
                i += 1;
            }
            tokens.push(Token { kind: TokenKind::Name(chars[start..i].iter().collect()), column });
        } else {
            let symbol = match (c, chars.get(i + 1)) {
                ('*', Some('*')) => "**",
                ('+', _) => "+",
                ('-', _) => "-",
                ('*', _) => "*",
                ('/', _) => "/",
                ('^', _) => "^",
                ('(', _) => "(",
                (')', _) => ")",
                (',', _) => ",",
                _ => {
                    return Err(fail(
                        column,
                        format!("`{c}` is not part of the grammar (numbers, x0 .. x(d-1), + - * / ^, functions)"),
                    ));
                }
            };
            i += symbol.len();
            tokens.push(Token { kind: TokenKind::Symbol(symbol), column });
        }
    }
    Ok(tokens)
}

struct Parser<'a> {
    text: &'a str,
    tokens: &'a [Token],
    at: usize,
    tape: Vec<Op>,
    /// The levels of nesting open at the token being read.
    depth: usize,
}

impl Parser<'_> {
    fn error(&self, column: usize, reason: &str) -> Error {
        Error::Parse { location: at_column(self.text, column), reason: reason.to_string() }
    }

    /// The column just past the end, for "the expression ended" errors.
    fn end(&self) -> usize {
        self.text.chars().count() + 1
    }

    fn peek_symbol(&self, symbols: &[&'static str]) -> Option<&'static str> {
        match self.tokens.get(self.at).map(|t| &t.kind) {
            Some(TokenKind::Symbol(s)) if symbols.contains(s) => Some(s),
            _ => None,
        }
    }

    fn expect(&mut self, symbol: &'static str, context: &str) -> Result<()> {
        if self.peek_symbol(&[symbol]).is_some() {
            self.at += 1;
            return Ok(());
        }
        Err(match self.tokens.get(self.at) {
            Some(t) => self.error(t.column, &format!("expected `{symbol}` {context}, found {}", t.kind.describe())),
            None => self.error(self.end(), &format!("expected `{symbol}` {context}, but the expression ended")),
        })
    }

    /// Appends `op`, folding it to a constant when its operands are constants.
    fn push(&mut self, op: Op) -> usize {
        let constant = |slot: usize| if let Op::Const(c) = self.tape[slot] { Some(c) } else { None };
        let operands = op.operands();
        if operands.iter().flatten().all(|&a| constant(a).is_some()) && !matches!(op, Op::Var(_)) {
            let value = op.scalar(|a| constant(a).unwrap_or(f64::NAN));
            // a constant operand is one slot, and the operands are the last ones pushed
            if let Some(&first) = operands.iter().flatten().min() {
                self.tape.truncate(first);
            }
            self.tape.push(Op::Const(value));
        } else {
            self.tape.push(op);
        }
        self.tape.len() - 1
    }

    fn sum(&mut self) -> Result<usize> {
        self.left_associative(
            Self::product,
            |s, a, b| if s == "+" { Op::Add(a, b) } else { Op::Sub(a, b) },
            &["+", "-"],
        )
    }

    fn product(&mut self) -> Result<usize> {
        self.left_associative(Self::unary, |s, a, b| if s == "*" { Op::Mul(a, b) } else { Op::Div(a, b) }, &["*", "/"])
    }

    /// `operand (symbol operand)*`, grouped from the left.
    fn left_associative(
        &mut self,
        operand: fn(&mut Self) -> Result<usize>,
        op: fn(&str, usize, usize) -> Op,
        symbols: &[&'static str],
    ) -> Result<usize> {
        let mut left = operand(self)?;
        while let Some(s) = self.peek_symbol(symbols) {
            self.at += 1;
            let right = operand(self)?;
            left = self.push(op(s, left, right));
        }
        Ok(left)
    }

    /// Every level of nesting passes here: a sign, a power's exponent, a parenthesis and a
    /// function's argument each parse a unary first.
    fn unary(&mut self) -> Result<usize> {
        self.depth += 1;
        if self.depth > MAX_NESTING {
            let column = self.tokens.get(self.at).map_or_else(|| self.end(), |t| t.column);
            return Err(self.error(
                column,
                &format!("nested more than {MAX_NESTING} levels deep (signs, powers, parentheses, function calls)"),
            ));
        }
        let value = self.signed();
        self.depth -= 1;
        value
    }

    fn signed(&mut self) -> Result<usize> {
        match self.peek_symbol(&["-", "+"]) {
            Some("-") => {
                self.at += 1;
                let a = self.unary()?;
                Ok(self.push(Op::Neg(a)))
            }
            Some(_) => {
                self.at += 1;
                self.unary()
            }
            None => self.power(),
        }
    }

    fn power(&mut self) -> Result<usize> {
        let base = self.atom()?;
        if self.peek_symbol(&["^", "**"]).is_some() {
            self.at += 1;
            let exponent = self.unary()?;
            return Ok(self.push(Op::Binary(f64::powf, base, exponent)));
        }
        Ok(base)
    }

    fn atom(&mut self) -> Result<usize> {
        let Some(token) = self.tokens.get(self.at) else {
            return Err(
                self.error(self.end(), "expected a number, a variable, a function or `(`, but the expression ended")
            );
        };
        self.at += 1;
        match &token.kind {
            TokenKind::Number(x) => Ok(self.push(Op::Const(*x))),
            TokenKind::Symbol("(") => {
                let inner = self.sum()?;
                self.expect(")", &format!("to close the `(` at column {}", token.column))?;
                Ok(inner)
            }
            TokenKind::Symbol(s) => {
                Err(self.error(token.column, &format!("expected a number, a variable, a function or `(`, found `{s}`")))
            }
            TokenKind::Name(name) => self.name(name, token.column),
        }
    }

    fn name(&mut self, name: &str, column: usize) -> Result<usize> {
        if let Some(k) = name.strip_prefix('x').filter(|k| !k.is_empty() && k.bytes().all(|b| b.is_ascii_digit())) {
            let k = k.parse::<usize>().ok().filter(|&k| k < MAX_VARIABLES).ok_or_else(|| {
                self.error(column, &format!("variable `{name}` is out of range (x0 .. x{})", MAX_VARIABLES - 1))
            })?;
            return Ok(self.push(Op::Var(k)));
        }
        match name {
            "pi" => return Ok(self.push(Op::Const(std::f64::consts::PI))),
            "e" => return Ok(self.push(Op::Const(std::f64::consts::E))),
            _ => {}
        }
        let unary = UNARY.iter().find(|(n, _)| *n == name).map(|(_, f)| *f);
        let binary = BINARY.iter().find(|(n, _)| *n == name).map(|(_, f)| *f);
        if unary.is_none() && binary.is_none() {
            let known: Vec<&str> = UNARY.iter().map(|(n, _)| *n).chain(BINARY.iter().map(|(n, _)| *n)).collect();
            return Err(self.error(
                column,
                &format!(
                    "unknown name `{name}` (variables x0, x1, ...; constants pi, e; functions {})",
                    known.join(", ")
                ),
            ));
        }
        self.expect("(", &format!("after the function `{name}`"))?;
        let a = self.sum()?;
        let op = match (unary, binary) {
            (Some(f), _) => Op::Unary(f, a),
            (None, Some(f)) => {
                self.expect(",", &format!("between the two arguments of `{name}`"))?;
                let b = self.sum()?;
                Op::Binary(f, a, b)
            }
            (None, None) => unreachable!("checked above"),
        };
        self.expect(")", &format!("to close `{name}(` at column {column}"))?;
        Ok(self.push(op))
    }
}
