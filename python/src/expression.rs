//! Set expressions written as nested Python tuples, read into the crate's
//! [`Expression`].
//!
//! An expression is an operand's index (an `int`, or a numpy integer,
//! naming a solid of the list) or a tuple (or list) `(operation, x, y, ...)` with `operation` one
//! of `"union"`, `"intersection"`, `"difference"` and at least two
//! sub-expressions after it: `("difference", 0, ("union", 1, 2))`. More than
//! two operands read as the operation applied left to right
//! (`("difference", 0, 1, 2)` is `0 − 1 − 2`), regrouped into a balanced
//! tree (`0 − (1 ∪ 2)` for a difference), which is the same set.
//!
//! Every refusal names the offending part by its place in the tuples, as
//! Python would index it: `expression[2][0]`.

use pyo3::prelude::*;
use pyo3::types::{PyBool, PyList, PyString, PyTuple};
use wingedge::SetOp;
use wingedge::boolean::Expression;

/// How deeply tuples may nest: deeper input is refused rather than risk
/// the stack (a long chain is written flat: `("union", 0, 1, 2, ...)`).
pub(crate) const MAX_DEPTH: usize = 1000;

/// Reads `expression` over `count` operands.
///
/// # Errors
///
/// A message naming the place of the first part that is neither an index
/// below `count` nor a tuple or list of a known operation and at least two
/// sub-expressions (the caller raises it as its exception class).
pub(crate) fn parse(expression: &Bound<'_, PyAny>, count: usize) -> Result<Expression, String> {
    parse_at(expression, count, &mut String::from("expression"), 0)
}

fn parse_at(
    part: &Bound<'_, PyAny>,
    count: usize,
    place: &mut String,
    depth: usize,
) -> Result<Expression, String> {
    if part.is_instance_of::<PyBool>() {
        return Err(format!(
            "{place}: {} is a bool, not an operand index",
            describe(part)
        ));
    }
    let items: Vec<Bound<'_, PyAny>> = if let Ok(t) = part.cast::<PyTuple>() {
        t.iter().collect()
    } else if let Ok(l) = part.cast::<PyList>() {
        l.iter().collect()
    } else {
        return operand(part, count, place);
    };
    if depth >= MAX_DEPTH {
        return Err(format!(
            "{place}: nested more than {MAX_DEPTH} levels deep; write long chains flat, \
             as (\"union\", 0, 1, 2, ...)"
        ));
    }
    let Some(head) = items.first() else {
        return Err(format!(
            "{place}: an empty tuple; expected (operation, x, y, ...)"
        ));
    };
    let operation = operation_of(head).ok_or_else(|| {
        format!(
            "{place}[0]: {} is not an operation; expected \"union\", \"intersection\" or \
             \"difference\"",
            describe(head)
        )
    })?;
    if items.len() < 3 {
        return Err(format!(
            "{place}: a {} needs at least two operands, got {}",
            SetOp::name(operation),
            items.len() - 1
        ));
    }
    let mut operands = Vec::with_capacity(items.len() - 1);
    for (i, item) in items.iter().enumerate().skip(1) {
        let length = place.len();
        place.push_str(&format!("[{i}]"));
        operands.push(parse_at(item, count, place, depth + 1)?);
        place.truncate(length);
    }
    Ok(match operation {
        SetOp::Union | SetOp::Intersection => balanced(operation, operands),
        SetOp::Difference | SetOp::ReverseDifference => {
            let rest = operands.split_off(1);
            let first = operands.pop().unwrap_or(Expression::Operand(0));
            Expression::of(operation, first, balanced(SetOp::Union, rest))
        }
    })
}

/// An operand's index: a Python `int` or anything with `__index__` (a
/// numpy integer), below `count`.
fn operand(part: &Bound<'_, PyAny>, count: usize, place: &str) -> Result<Expression, String> {
    // `operator.index`: ints and numpy integers, never a float.
    let index = part
        .py()
        .import("operator")
        .and_then(|m| m.getattr("index"))
        .and_then(|index| index.call1((part,)));
    let Ok(index) = index else {
        return Err(format!(
            "{place}: expected an operand index or a tuple (operation, x, y, ...), got {}",
            describe(part)
        ));
    };
    match index.extract::<i64>() {
        Ok(k) if usize::try_from(k).is_ok_and(|k| k < count) => Ok(Expression::Operand(k as usize)),
        _ => Err(format!(
            "{place}: operand {} names no solid; {count} solids were given (indices 0 to {})",
            describe(part),
            count as i64 - 1
        )),
    }
}

/// `x₀ op x₁ op …` for an associative `op`, grouped as a balanced tree
/// (depth `log₂ n`, not `n`). `parts` is never empty.
fn balanced(operation: SetOp, mut parts: Vec<Expression>) -> Expression {
    if parts.len() == 1 {
        return parts.pop().unwrap_or(Expression::Operand(0));
    }
    let right = parts.split_off(parts.len() / 2);
    Expression::of(
        operation,
        balanced(operation, parts),
        balanced(operation, right),
    )
}

fn operation_of(head: &Bound<'_, PyAny>) -> Option<SetOp> {
    let word: String = head.cast::<PyString>().ok()?.extract().ok()?;
    match word.as_str() {
        "union" => Some(SetOp::Union),
        "intersection" => Some(SetOp::Intersection),
        "difference" => Some(SetOp::Difference),
        _ => None,
    }
}

/// `repr(part)` (its first 60 characters) and its type.
fn describe(part: &Bound<'_, PyAny>) -> String {
    let text = part
        .repr()
        .map(|r| r.to_string())
        .unwrap_or_else(|_| String::from("?"));
    let short: String = text.chars().take(60).collect();
    let ellipsis = if short.len() < text.len() { "..." } else { "" };
    let kind = part
        .get_type()
        .name()
        .map(|n| n.to_string())
        .unwrap_or_default();
    format!("{short}{ellipsis} ({kind})")
}
