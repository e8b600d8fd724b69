//! The pest parser generated from `grammar/expr.pest` and `grammar/scene.pest`, and the words a user
//! reads for the expression rules.
//!
//! The scene grammar is the second `#[grammar = ...]` attribute of the same struct, so that it reuses
//! the rule `expr`; its own rules have no words here (the scene's are in `scene/error.rs`).

use pest_derive::Parser;

/// The generated parser; its rules are the enum `Rule`.
#[derive(Parser)]
#[grammar = "../grammar/expr.pest"]
#[grammar = "../grammar/scene.pest"]
pub(crate) struct Grammar;

/// What a parse error says was expected at its position, in a user's words.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Expected {
    /// Something to compute with: a number, a name, `(` or a function call.
    Operand,
    /// A binary operator (implicit multiplication included).
    Operator,
    /// The `)` that closes an open `(`.
    CloseParen,
    /// The end of the expression.
    End,
}

impl Expected {
    /// The words for this expectation.
    pub fn words(self) -> &'static str {
        match self {
            Expected::Operand => "a number, a name, `(` or a function call",
            Expected::Operator => "an operator such as `+` or `*`",
            Expected::CloseParen => "`)`",
            Expected::End => "the end of the expression",
        }
    }

    /// What pest's attempt at `rule` means to a user; `None` for rules that are no part of the
    /// expression language (such as the scene grammar's). This is the one mapping from rule names
    /// to words.
    pub(crate) fn of_rule(rule: Rule) -> Option<Expected> {
        match rule {
            Rule::expr
            | Rule::neg
            | Rule::pos
            | Rule::degrees
            | Rule::number
            | Rule::call
            | Rule::callee
            | Rule::name
            | Rule::paren => Some(Expected::Operand),
            Rule::add | Rule::sub | Rule::mul | Rule::div | Rule::pow | Rule::implicit_mul => {
                Some(Expected::Operator)
            }
            Rule::EOI => Some(Expected::End),
            // `expr_input` is only ever the whole input; the scene grammar's rules are not ours.
            #[allow(unreachable_patterns)]
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    //! The rule `expr` inside a larger, line-based grammar, as the scene grammar will use it.

    use pest::Parser;

    #[derive(pest_derive::Parser)]
    #[grammar = "../grammar/expr.pest"]
    #[grammar_inline = r#"
statement = { SOI ~ keyword ~ field* ~ EOI }
keyword = @{ ASCII_ALPHA+ }
field = { field_name ~ "=" ~ (vector | expr) }
field_name = @{ ASCII_ALPHA+ }
vector = { "[" ~ expr ~ ("," ~ expr)* ~ "]" }
"#]
    struct SceneLike;

    /// The text of every `expr` directly under a field or a vector.
    fn fields(line: &str) -> Vec<String> {
        let statement = SceneLike::parse(Rule::statement, line)
            .unwrap_or_else(|e| panic!("{line}: {e}"))
            .next()
            .expect("a statement");
        statement
            .into_inner()
            .filter(|p| p.as_rule() == Rule::field)
            .flat_map(|f| f.into_inner().skip(1))
            .flat_map(|v| match v.as_rule() {
                Rule::vector => v.into_inner().map(|e| e.as_str().to_string()).collect(),
                _ => vec![v.as_str().trim().to_string()],
            })
            .collect()
    }

    #[test]
    fn expressions_end_before_the_next_field() {
        let rows: [(&str, &[&str]); 4] = [
            (
                "joint a=l1  alpha=0  d=0  theta=q1",
                &["l1", "0", "0", "q1"],
            ),
            (
                "joint a=0  alpha=-90deg  d=q1  theta=0",
                &["0", "-90deg", "q1", "0"],
            ),
            (
                "link mass=m1  com=[lc1-l1,0,0]",
                &["m1", "lc1-l1", "0", "0"],
            ),
            ("gravity g=[0, -g, 0]", &["0", "-g", "0"]),
        ];
        for (line, want) in rows {
            assert_eq!(fields(line), want, "{line}");
        }
    }
}
