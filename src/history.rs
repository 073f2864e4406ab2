//! Load histories: one factor $\varphi(t)$ scales both loads,
//! $f_0(t) = \varphi(t)\,f_0$ and $f_2(t) = \varphi(t)\,f_2$, and backward Euler reads the
//! load at the end of each step, $f_n = \varphi(t_n)\,f$.
//!
//! The paper's hypothesis H(f) asks for $f_0 \in H^1(0,T;L^2)$, $f_2 \in H^1(0,T;L^2(\Gamma_2))$,
//! $f_0(0) \in V$ and $f_2(0) = 0$; with $u_0 = 0$ the compatibility condition of H(0) asks
//! the same of $f(0)$. A constant load ($\varphi \equiv 1$) breaks both unless the loads
//! vanish; a history with $\varphi(0) = 0$ meets them whatever the loads. Every
//! $\varphi$ offered here is Lipschitz, hence in $H^1(0, T)$.

use crate::error::InputError;
use std::fmt;

/// The factor $\varphi(t)$ of a load history.
// ANCHOR: history
#[derive(Debug, Clone, PartialEq, Default)]
pub enum History {
    /// φ ≡ 1: the load acts in full from t = 0 (the paper's scenes).
    #[default]
    Constant,
    /// φ(t) = min(t / t_r, 1): a linear ramp to the full load at t_r.
    Ramp {
        /// The ramp time $t_r$ at which the full load is reached.
        t_r: f64,
    },
    /// φ piecewise linear through (t_i, φ_i), t_i strictly increasing.
    Table {
        /// The points $(t_i, \varphi_i)$; before the first and after the last, φ
        /// keeps the end value.
        points: Vec<(f64, f64)>,
    },
}

impl History {
    /// φ(t).
    pub fn phi(&self, t: f64) -> f64 {
        match self {
            History::Constant => 1.0,
            History::Ramp { t_r } => (t / t_r).min(1.0),
            History::Table { points } => {
                let i = points.partition_point(|p| p.0 <= t);
                if i == 0 {
                    return points[0].1;
                }
                if i == points.len() {
                    return points[i - 1].1;
                }
                let ((t0, p0), (t1, p1)) = (points[i - 1], points[i]);
                if t == t0 {
                    return p0;
                }
                p0 + (p1 - p0) * ((t - t0) / (t1 - t0))
            }
        }
    }
    // ANCHOR_END: history

    /// The times at which $\varphi$ has a kink: the ramp's end, the table's points
    /// (none for a constant load). The reconstruction's quadrature in time
    /// ([`crate::reconstruction::time_points`]) is cut there.
    pub fn breaks(&self) -> Vec<f64> {
        match self {
            History::Constant => vec![],
            History::Ramp { t_r } => vec![*t_r],
            History::Table { points } => points.iter().map(|p| p.0).collect(),
        }
    }

    /// Whether $\varphi(0) = 0$: then $f(0) = 0$, which meets H(f)'s $f_0(0) \in V$,
    /// $f_2(0) = 0$ and H(0)'s compatibility at $u_0 = 0$ for any loads.
    pub fn starts_at_zero(&self) -> bool {
        self.phi(0.0) == 0.0
    }

    /// Checks the history on $[0, T]$; `field` names it in errors.
    pub fn validate(&self, field: &str, t_end: f64) -> Result<(), InputError> {
        match self {
            History::Constant => Ok(()),
            History::Ramp { t_r } => check_ramp(&format!("{field}.ramp"), *t_r, t_end).map(|_| ()),
            History::Table { points } => {
                let field = format!("{field}.table");
                if points.len() < 2 {
                    return Err(InputError::field(
                        &field,
                        format!("{} point(s)", points.len()),
                        "at least two points [t, phi]",
                    ));
                }
                for (i, &(t, p)) in points.iter().enumerate() {
                    if !t.is_finite() || !p.is_finite() || p.abs() > 1e12 {
                        return Err(InputError::field(
                            format!("{field}[{i}]"),
                            format!("[{t}, {p}]"),
                            "a point [t, phi] of finite numbers, |phi| <= 1e12",
                        ));
                    }
                    if i > 0 && t <= points[i - 1].0 {
                        return Err(InputError::field(
                            format!("{field}[{i}]"),
                            format!("t = {t} after t = {}", points[i - 1].0),
                            "times strictly increasing",
                        ));
                    }
                }
                let (first, last) = (points[0].0, points[points.len() - 1].0);
                if first > 0.0 || last < t_end {
                    return Err(InputError::field(
                        &field,
                        format!("times from {first} to {last}"),
                        format!("times covering [0, T] = [0, {t_end}]"),
                    ));
                }
                Ok(())
            }
        }
    }

    /// Reads the TOML value of `loads.history`: `"constant"`, `{ ramp = t_r }` or
    /// `{ table = [[t, phi], ...] }`. The values are checked by [`History::validate`].
    pub fn from_toml(field: &str, v: &toml::Value) -> Result<History, InputError> {
        const ALLOWED: &str =
            "\"constant\", { ramp = T_R } or { table = [[t, phi], ...] } (see the book, \"Time\")";
        let num = |f: &str, x: &toml::Value| -> Result<f64, InputError> {
            match x {
                toml::Value::Float(x) => Ok(*x),
                toml::Value::Integer(i) => Ok(*i as f64),
                other => Err(InputError::field(f, other, "a number")),
            }
        };
        match v {
            toml::Value::String(s) if s == "constant" => Ok(History::Constant),
            toml::Value::Table(t) if t.len() == 1 => {
                let (key, val) = t.iter().next().expect("one entry");
                match key.as_str() {
                    "ramp" => Ok(History::Ramp {
                        t_r: num(&format!("{field}.ramp"), val)?,
                    }),
                    "table" => {
                        let f = format!("{field}.table");
                        let rows = val
                            .as_array()
                            .ok_or_else(|| InputError::field(&f, val, "an array of [t, phi]"))?;
                        let mut points = Vec::with_capacity(rows.len());
                        for (i, row) in rows.iter().enumerate() {
                            let fi = format!("{f}[{i}]");
                            match row.as_array().map(Vec::as_slice) {
                                Some([t, p]) => points.push((num(&fi, t)?, num(&fi, p)?)),
                                _ => {
                                    return Err(InputError::field(
                                        fi,
                                        row,
                                        "a point [t, phi] of exactly two numbers",
                                    ));
                                }
                            }
                        }
                        Ok(History::Table { points })
                    }
                    _ => Err(InputError::field(field, v, ALLOWED)),
                }
            }
            _ => Err(InputError::field(field, v, ALLOWED)),
        }
    }

    /// A short name for tables and file names: `constant`, `ramp0.25`, `table`.
    pub fn label(&self) -> String {
        match self {
            History::Constant => "constant".into(),
            History::Ramp { t_r } => format!("ramp{t_r}"),
            History::Table { .. } => "table".into(),
        }
    }
}

/// A ramp time $t_r$ for a run of length $T$: in $[10^{-12}T, 10^{12}T]$.
pub fn check_ramp(field: &str, t_r: f64, t_end: f64) -> Result<f64, InputError> {
    crate::error::in_range(field, t_r, 1e-12 * t_end, 1e12 * t_end)
}

/// The history as a reader would write it in TOML (no commas, so it fits a CSV cell).
impl fmt::Display for History {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            History::Constant => write!(f, "constant"),
            History::Ramp { t_r } => write!(f, "ramp t_r = {t_r}"),
            History::Table { points } => {
                write!(f, "table")?;
                for (t, p) in points {
                    write!(f, " ({t} {p})")?;
                }
                Ok(())
            }
        }
    }
}
