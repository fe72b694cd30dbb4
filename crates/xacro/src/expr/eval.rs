//! Tree-walking evaluator.

use std::cell::Cell;
use std::cmp::Ordering;
use std::rc::Rc;

use super::builtins;
use super::ops::{self, check_items};
use super::parser::{Arg, BinOp, CmpOp, CompKind, Kind, Node, Target};
use super::value::{py_cmp, py_eq};
use super::{EvalError, Scope, Value};

/// Most steps in one evaluation: nodes evaluated, loop iterations (comprehension steps, items built by
/// `range` and friends) and the values visited by deep operations (comparisons, membership tests, `str()`).
const STEP_BUDGET: u64 = 2_000_000;

thread_local! {
    /// The steps left to the innermost evaluation running on this thread, and whether it ran out. A
    /// thread-local rather than a `Ctx` field so that the deep operations of [`super::value`] (`==`, `<`,
    /// `repr`), called from everywhere, are charged too: containers share their items, so a short
    /// expression can build a list whose comparison or `str()` visits exponentially many values.
    static BUDGET: Cell<(u64, bool)> = const { Cell::new((u64::MAX, false)) };
}

/// Spend `n` steps of the running evaluation's budget. False when it ran out: the caller stops early, and
/// the evaluation fails with [`budget_error`] as soon as the current node is done (see [`Ctx::eval`]).
pub(crate) fn charge(n: usize) -> bool {
    BUDGET.with(|b| {
        let (left, exhausted) = b.get();
        let n = n as u64;
        if exhausted || n > left {
            b.set((0, true));
            false
        } else {
            b.set((left - n, false));
            true
        }
    })
}

fn budget_exhausted() -> bool {
    BUDGET.with(|b| b.get().1)
}

pub(crate) fn budget_error() -> EvalError {
    EvalError::new("MemoryError", "evaluation too long (step budget exhausted)")
}

/// Evaluation state: the host scope, comprehension variables, and the step budget of the enclosing
/// evaluation (restored on drop: properties are evaluated lazily, inside other evaluations).
pub(crate) struct Ctx<'a> {
    pub(crate) scope: &'a dyn Scope,
    locals: Vec<(Rc<str>, Value)>,
    outer_budget: (u64, bool),
}

impl Drop for Ctx<'_> {
    fn drop(&mut self) {
        BUDGET.with(|b| b.set(self.outer_budget));
    }
}

/// Call arguments after evaluation.
pub(crate) struct Args {
    pub(crate) pos: Vec<Value>,
    pub(crate) kw: Vec<(String, Value)>,
}

fn with_offset(mut e: EvalError, offset: usize) -> EvalError {
    if e.offset.is_none() {
        e.offset = Some(offset);
    }
    e
}

impl<'a> Ctx<'a> {
    pub(crate) fn new(scope: &'a dyn Scope) -> Self {
        Ctx {
            scope,
            locals: Vec::new(),
            outer_budget: BUDGET.with(|b| b.replace((STEP_BUDGET, false))),
        }
    }

    /// Spend `n` steps of the budget.
    pub(crate) fn spend(&mut self, n: usize) -> Result<(), EvalError> {
        if charge(n) {
            Ok(())
        } else {
            Err(budget_error())
        }
    }

    pub(crate) fn eval(&mut self, node: &Node) -> Result<Value, EvalError> {
        // Every node evaluated costs a step: a comprehension's element is charged for its whole
        // expression, not once per item (nested loops over strings ran for seconds under the budget).
        self.spend(1).map_err(|e| with_offset(e, node.offset))?;
        let result = match self.eval_inner(node) {
            // A deep operation ran out of budget and returned early: its result is not to be trusted.
            _ if budget_exhausted() => Err(budget_error()),
            result => result,
        };
        result.map_err(|e| with_offset(e, node.offset))
    }

    fn eval_inner(&mut self, node: &Node) -> Result<Value, EvalError> {
        match &node.kind {
            Kind::Const(v) => Ok(v.clone()),
            Kind::Name(n) => self.lookup(n),
            Kind::Attr(obj, name) => {
                let obj = self.eval(obj)?;
                builtins::get_attr(&obj, name)
            }
            Kind::Index(obj, idx) => {
                let obj = self.eval(obj)?;
                let idx = self.eval(idx)?;
                builtins::index(&obj, &idx)
            }
            Kind::Slice(obj, lo, hi, step) => {
                let obj = self.eval(obj)?;
                let mut bound = |n: &Option<Box<Node>>| -> Result<Value, EvalError> {
                    match n {
                        Some(n) => self.eval(n),
                        None => Ok(Value::None),
                    }
                };
                let (lo, hi, step) = (bound(lo)?, bound(hi)?, bound(step)?);
                builtins::slice(&obj, &lo, &hi, &step)
            }
            Kind::Call(func, args) => self.call(func, args),
            Kind::Unary(op, x) => {
                let x = self.eval(x)?;
                ops::unary(*op, &x)
            }
            Kind::Binary(op, a, b) => {
                let a = self.eval(a)?;
                let b = self.eval(b)?;
                ops::binary(*op, &a, &b)
            }
            Kind::Compare(first, rest) => {
                let mut left = self.eval(first)?;
                for (op, right) in rest {
                    let right = self.eval(right)?;
                    if !compare(*op, &left, &right)? {
                        return Ok(Value::Bool(false));
                    }
                    left = right;
                }
                Ok(Value::Bool(true))
            }
            Kind::And(a, b) => {
                let a = self.eval(a)?;
                if a.is_truthy() {
                    self.eval(b)
                } else {
                    Ok(a)
                }
            }
            Kind::Or(a, b) => {
                let a = self.eval(a)?;
                if a.is_truthy() {
                    Ok(a)
                } else {
                    self.eval(b)
                }
            }
            Kind::Not(x) => Ok(Value::Bool(!self.eval(x)?.is_truthy())),
            Kind::IfElse(cond, a, b) => {
                if self.eval(cond)?.is_truthy() {
                    self.eval(a)
                } else {
                    self.eval(b)
                }
            }
            Kind::List(items) => Ok(Value::list(self.eval_all(items)?)),
            Kind::Tuple(items) => Ok(Value::tuple(self.eval_all(items)?)),
            Kind::Dict(items) => {
                let mut pairs = Vec::with_capacity(items.len());
                for (k, v) in items {
                    let k = self.eval(k)?;
                    builtins::check_hashable(&k)?;
                    pairs.push((k, self.eval(v)?));
                }
                Ok(Value::dict(pairs))
            }
            Kind::Comp(kind, elt, value, clauses) => {
                let mut out = Vec::new();
                let mark = self.locals.len();
                let r = self.comprehension(clauses, 0, &mut |ctx| {
                    let k = ctx.eval(elt)?;
                    let v = match value {
                        Some(v) => Some(ctx.eval(v)?),
                        None => None,
                    };
                    out.push((k, v));
                    check_items(out.len())
                });
                self.locals.truncate(mark);
                r?;
                Ok(match kind {
                    CompKind::List => Value::list(out.into_iter().map(|(k, _)| k).collect()),
                    CompKind::Dict => {
                        for (k, _) in &out {
                            builtins::check_hashable(k)?;
                        }
                        Value::dict(
                            out.into_iter()
                                .map(|(k, v)| (k, v.unwrap_or(Value::None)))
                                .collect(),
                        )
                    }
                })
            }
        }
    }

    fn eval_all(&mut self, items: &[Node]) -> Result<Vec<Value>, EvalError> {
        items.iter().map(|n| self.eval(n)).collect()
    }

    fn comprehension(
        &mut self,
        clauses: &[super::parser::Clause],
        i: usize,
        emit: &mut dyn FnMut(&mut Self) -> Result<(), EvalError>,
    ) -> Result<(), EvalError> {
        let Some(clause) = clauses.get(i) else {
            return emit(self);
        };
        let iterable = self.eval(&clause.iter)?;
        let items = builtins::iterate(&iterable)?;
        'items: for item in items {
            self.spend(1)?;
            let mark = self.locals.len();
            self.bind(&clause.target, item)?;
            for cond in &clause.conds {
                if !self.eval(cond)?.is_truthy() {
                    self.locals.truncate(mark);
                    continue 'items;
                }
            }
            let r = self.comprehension(clauses, i + 1, emit);
            self.locals.truncate(mark);
            r?;
        }
        Ok(())
    }

    fn bind(&mut self, target: &Target, value: Value) -> Result<(), EvalError> {
        match target {
            Target::Name(n) => {
                self.locals.push((n.clone(), value));
                Ok(())
            }
            Target::Tuple(targets) => {
                let items = builtins::iterate(&value)?;
                if items.len() < targets.len() {
                    return Err(EvalError::new(
                        "ValueError",
                        format!(
                            "not enough values to unpack (expected {}, got {})",
                            targets.len(),
                            items.len()
                        ),
                    ));
                }
                if items.len() > targets.len() {
                    return Err(EvalError::new(
                        "ValueError",
                        format!("too many values to unpack (expected {})", targets.len()),
                    ));
                }
                for (t, v) in targets.iter().zip(items) {
                    self.bind(t, v)?;
                }
                Ok(())
            }
        }
    }

    fn lookup(&mut self, name: &str) -> Result<Value, EvalError> {
        if let Some((_, v)) = self.locals.iter().rev().find(|(n, _)| &**n == name) {
            return Ok(v.clone());
        }
        if let Some(v) = self.scope.lookup(name)? {
            return Ok(v);
        }
        builtins::global(name).ok_or_else(|| EvalError {
            kind: "NameError",
            message: format!("name '{name}' is not defined"),
            undefined_name: Some(name.to_string()),
            offset: None,
        })
    }

    fn eval_args(&mut self, args: &[Arg]) -> Result<Args, EvalError> {
        let mut out = Args {
            pos: Vec::with_capacity(args.len()),
            kw: Vec::new(),
        };
        for a in args {
            match a {
                Arg::Pos(n) => out.pos.push(self.eval(n)?),
                Arg::Star(n) => {
                    let v = self.eval(n)?;
                    out.pos.extend(builtins::iterate(&v)?);
                }
                Arg::Kw(name, n) => {
                    let v = self.eval(n)?;
                    push_kw(&mut out.kw, name.to_string(), v)?;
                }
                Arg::StarStar(n) => match self.eval(n)? {
                    Value::Dict(items) => {
                        for (k, v) in items.iter() {
                            let Value::Str(k) = k else {
                                return Err(EvalError::new(
                                    "TypeError",
                                    "keywords must be strings",
                                ));
                            };
                            push_kw(&mut out.kw, k.to_string(), v.clone())?;
                        }
                    }
                    other => {
                        return Err(EvalError::new(
                            "TypeError",
                            format!(
                                "argument after ** must be a mapping, not {}",
                                other.type_name()
                            ),
                        ))
                    }
                },
            }
        }
        Ok(out)
    }

    fn call(&mut self, func: &Node, args: &[Arg]) -> Result<Value, EvalError> {
        if let Kind::Attr(obj, name) = &func.kind {
            let obj = self.eval(obj)?;
            if builtins::is_method(&obj, name) {
                let args = self.eval_args(args)?;
                return builtins::call_method(self, &obj, name, args)
                    .map_err(|e| with_offset(e, func.offset));
            }
            let f = builtins::get_attr(&obj, name).map_err(|e| with_offset(e, func.offset))?;
            let args = self.eval_args(args)?;
            return self.call_value(&f, args);
        }
        let f = self.eval(func)?;
        let args = self.eval_args(args)?;
        self.call_value(&f, args)
    }

    /// Call a function value.
    pub(crate) fn call_value(&mut self, f: &Value, args: Args) -> Result<Value, EvalError> {
        match f {
            Value::Function(name) => builtins::call(self, name, args),
            other => Err(EvalError::new(
                "TypeError",
                format!("'{}' object is not callable", other.type_name()),
            )),
        }
    }
}

fn push_kw(kw: &mut Vec<(String, Value)>, name: String, v: Value) -> Result<(), EvalError> {
    if kw.iter().any(|(n, _)| *n == name) {
        return Err(EvalError::new(
            "TypeError",
            format!("got multiple values for keyword argument '{name}'"),
        ));
    }
    kw.push((name, v));
    Ok(())
}

/// One comparison of a chain.
fn compare(op: CmpOp, a: &Value, b: &Value) -> Result<bool, EvalError> {
    let ord = |sym: &str| py_cmp(a, b, sym);
    Ok(match op {
        CmpOp::Eq => py_eq(a, b),
        CmpOp::Ne => !py_eq(a, b),
        CmpOp::Lt => ord("<")? == Some(Ordering::Less),
        CmpOp::Le => matches!(ord("<=")?, Some(Ordering::Less | Ordering::Equal)),
        CmpOp::Gt => ord(">")? == Some(Ordering::Greater),
        CmpOp::Ge => matches!(ord(">=")?, Some(Ordering::Greater | Ordering::Equal)),
        CmpOp::In => ops::contains(b, a)?,
        CmpOp::NotIn => !ops::contains(b, a)?,
        CmpOp::Is => ops::is_same(a, b),
        CmpOp::IsNot => !ops::is_same(a, b),
    })
}

/// `BinOp` is re-exported for builtins that apply operators (`sum`).
pub(crate) fn add(a: &Value, b: &Value) -> Result<Value, EvalError> {
    ops::binary(BinOp::Add, a, b)
}
