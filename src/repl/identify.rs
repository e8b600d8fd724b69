//! The identification queries: `regressor`, `regressor k`, `base`, `base NAME` (see
//! [`crate::identify`]).

use super::{Command, ReplError, Session};
use crate::algebra::compact::identity::ProofOptions;
use crate::identify::base::Fate;
use crate::identify::render::{self, proof_summary};
use crate::identify::{base_parameters, BaseOptions, Regressor, RegressorOptions};
use crate::print::poly::poly_to_string;
use crate::print::Style;

impl Session {
    /// Answers `regressor`, `regressor k`, `base`, `base NAME`.
    pub(super) fn identification(&self, cmd: &Command) -> Result<String, ReplError> {
        let math = |e: crate::identify::IdentifyError| ReplError::Math(e.to_string());
        let reg = Regressor::build(self.der.robot(), RegressorOptions::default()).map_err(math)?;
        let style: Style = self.style;
        let tau_proof = reg.prove_tau(&ProofOptions::default());
        match cmd {
            Command::Regressor(None) => Ok(render::text(&reg, None, &tau_proof, style)
                .trim_end()
                .to_string()),
            Command::Regressor(Some(k)) => {
                let n = reg.dof();
                if *k < 1 || *k > n {
                    return Err(ReplError::Index {
                        query: format!("regressor {k}"),
                        dof: n,
                        low: 1,
                    });
                }
                let mut ex = reg.arena.expander(render::DISPLAY_BUDGET);
                let lines: Vec<String> = reg.y[k - 1]
                    .iter()
                    .enumerate()
                    .filter(|(_, e)| !e.is_zero())
                    .map(|(c, e)| {
                        let shown = ex.expand(e).unwrap_or_else(|_| e.clone());
                        format!(
                            "Y{k}[{}] = {}",
                            reg.params[c].name(),
                            poly_to_string(&shown, style)
                        )
                    })
                    .collect();
                Ok(lines.join("\n"))
            }
            Command::Base(which) => {
                let b = base_parameters(&reg, &BaseOptions::default()).map_err(math)?;
                match which {
                    None => Ok(render::base_text(&reg, &b, style).trim_end().to_string()),
                    Some(name) => {
                        let p = b.find(name).ok_or_else(|| {
                            ReplError::Math(format!(
                                "no base parameter `{name}`: they are {}",
                                b.base
                                    .iter()
                                    .map(|p| p.name.as_str())
                                    .collect::<Vec<_>>()
                                    .join(" ")
                            ))
                        })?;
                        let mut out = match b.expression(p, &reg.params) {
                            Some(e) => format!("{} = {}", p.name, poly_to_string(&e, style)),
                            None => format!(
                                "{} groups {}",
                                p.name,
                                p.terms
                                    .iter()
                                    .map(|(k, _)| reg.params[*k].name())
                                    .collect::<Vec<_>>()
                                    .join(", ")
                            ),
                        };
                        for rule in &p.rules {
                            out.push_str(&format!("\n  rule: {rule}"));
                        }
                        let grouped: Vec<String> = b
                            .eliminated
                            .iter()
                            .filter(|(_, f)| matches!(f, Fate::Grouped { into, .. } if into.iter().any(|&r| b.base[r].name == p.name)))
                            .map(|(k, _)| reg.params[*k].name())
                            .collect();
                        if !grouped.is_empty() {
                            out.push_str(&format!("\n  grouped into it: {}", grouped.join(" ")));
                        }
                        let (holds, how) = proof_summary(&b.dependency_proofs);
                        if b.coefficients.is_ok() {
                            out.push_str(&format!(
                                "\n  {} [{how}]: Y_beta beta = Y pi",
                                if holds { "proved" } else { "NOT proved" }
                            ));
                        }
                        Ok(out)
                    }
                }
            }
            _ => unreachable!("only identification commands are routed here"),
        }
    }
}
