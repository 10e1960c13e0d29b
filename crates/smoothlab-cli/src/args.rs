//! What the commands share, below them and below `files`: the value parsers of the core's
//! named choices (the possible values and their help come from the core's enums) and how
//! a count is written in a message.

use smoothlab::io::MshVersion;
use smoothlab::objective::Penalty;
use smoothlab::smooth::{Order, Strategy};

/// A value parser for one of the core's named choices: the possible values are `all`'s
/// names with their descriptions, in the core's order, so the CLI lists exactly what the
/// core offers (no mirror enum to keep in step with it).
pub fn named<T: Copy + Send + Sync + 'static>(
    all: &'static [T],
    name: fn(T) -> &'static str,
    describe: fn(T) -> &'static str,
) -> impl clap::builder::TypedValueParser<Value = T> {
    use clap::builder::{PossibleValue, TypedValueParser};
    clap::builder::PossibleValuesParser::new(all.iter().map(|&t| PossibleValue::new(name(t)).help(describe(t))))
        .map(move |s: String| *all.iter().find(|&&t| name(t) == s).expect("one of the possible values"))
}

/// `--penalty`'s values.
pub fn penalty_parser() -> impl clap::builder::TypedValueParser<Value = Penalty> {
    named(&Penalty::ALL, Penalty::name, Penalty::describe)
}

/// `--strategy`'s values.
pub fn strategy_parser() -> impl clap::builder::TypedValueParser<Value = Strategy> {
    named(&Strategy::ALL, Strategy::name, Strategy::describe)
}

/// `--order`'s values.
pub fn order_parser() -> impl clap::builder::TypedValueParser<Value = Order> {
    named(&Order::ALL, Order::name, Order::describe)
}

/// `--msh-version`'s values.
pub fn msh_version_parser() -> impl clap::builder::TypedValueParser<Value = MshVersion> {
    named(&MshVersion::ALL, MshVersion::name, MshVersion::describe)
}

/// A value per axis, `V` (the same on x, y and z) or `VX,VY,VZ`: `--cells 8`,
/// `--cells 8,4,2`, `--size 2,1,1`.
pub fn per_axis<T: std::str::FromStr + Copy>(s: &str) -> Result<[T; 3], String> {
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    let parse = |p: &str| p.parse::<T>().map_err(|_| format!("'{p}' is not a number of the kind wanted"));
    match parts.as_slice() {
        [one] => Ok([parse(one)?; 3]),
        [x, y, z] => Ok([parse(x)?, parse(y)?, parse(z)?]),
        _ => Err(format!("'{s}': give one value for every axis, or three separated by commas (x,y,z)")),
    }
}

/// `n` and the noun in its number: "1 tetrahedron", "6 tetrahedra", "0 quads".
pub fn count(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}
