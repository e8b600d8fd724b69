//! The benchmark robots: the example scenes (embedded in the binary, so `symdyn bench` runs from any
//! directory) and the generic chains of [`crate::chains`].

use super::BenchError;
use crate::chains;
use crate::dynamics::Robot;
use crate::parse::{parse_robot, urdf::UrdfOptions};

/// The example robots, by name, with their file under `examples/` and its text, in the order they are
/// reported: the scenes of the textbook arms, then two robots as practitioners have them, the UR5 and
/// the Franka Panda from their URDF files (numeric parameters, joints placed by `origin ... axis`).
pub const EXAMPLES: [(&str, &str, &str); 9] = [
    ("ppp", "ppp.scene", include_str!("../../examples/ppp.scene")),
    (
        "elbow",
        "elbow.scene",
        include_str!("../../examples/elbow.scene"),
    ),
    ("rpp", "rpp.scene", include_str!("../../examples/rpp.scene")),
    (
        "scara",
        "scara.scene",
        include_str!("../../examples/scara.scene"),
    ),
    (
        "stanford",
        "stanford.scene",
        include_str!("../../examples/stanford.scene"),
    ),
    (
        "puma560",
        "puma560.scene",
        include_str!("../../examples/puma560.scene"),
    ),
    (
        "puma560_symbolic",
        "puma560_symbolic.scene",
        include_str!("../../examples/puma560_symbolic.scene"),
    ),
    (
        "ur5.urdf",
        "ur5.urdf",
        include_str!("../../examples/ur5.urdf"),
    ),
    (
        "panda.urdf",
        "panda.urdf",
        include_str!("../../examples/panda.urdf"),
    ),
];

/// A benchmark robot: an example scene or the generic `n`-joint chain.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum RobotSpec {
    /// An example scene, by name (`ppp`, `puma560`, ...).
    Example(&'static str),
    /// `chains::chain(n)`.
    Chain(usize),
}

impl RobotSpec {
    /// Parses `ppp`, `puma560_symbolic`, `chain-5`, ... (the names [`RobotSpec::name`] gives).
    pub fn parse(s: &str) -> Result<RobotSpec, BenchError> {
        if let Some(n) = s.strip_prefix("chain-") {
            return match n.parse::<usize>() {
                Ok(n) if (1..=64).contains(&n) => Ok(RobotSpec::Chain(n)),
                _ => Err(BenchError::UnknownRobot(s.to_string())),
            };
        }
        EXAMPLES
            .iter()
            .find(|(name, _, _)| *name == s)
            .map(|(name, _, _)| RobotSpec::Example(name))
            .ok_or_else(|| BenchError::UnknownRobot(s.to_string()))
    }

    /// The name used in records and on the command line.
    pub fn name(&self) -> String {
        match self {
            RobotSpec::Example(name) => name.to_string(),
            RobotSpec::Chain(n) => format!("chain-{n}"),
        }
    }

    /// The scene text (or URDF).
    pub fn scene(&self) -> String {
        match self {
            RobotSpec::Example(name) => EXAMPLES
                .iter()
                .find(|(n, _, _)| n == name)
                .map(|(_, _, text)| text.to_string())
                .unwrap_or_default(),
            RobotSpec::Chain(n) => chains::chain_scene(*n),
        }
    }

    /// An example's file under `examples/` (`ppp.scene`, `ur5.urdf`); `None` for a chain.
    pub fn file(&self) -> Option<&'static str> {
        match self {
            RobotSpec::Example(name) => EXAMPLES
                .iter()
                .find(|(n, _, _)| n == name)
                .map(|(_, file, _)| *file),
            RobotSpec::Chain(_) => None,
        }
    }

    /// The robot, parsed from [`RobotSpec::scene`] (a scene or a URDF file, as its text says).
    pub fn robot(&self) -> Result<Robot, BenchError> {
        parse_robot(&self.scene(), &UrdfOptions::default())
            .map(|s| s.robot)
            .map_err(|e| BenchError::Robot {
                robot: self.name(),
                message: e.render(&self.name()),
            })
    }

    /// Every example scene.
    pub fn examples() -> Vec<RobotSpec> {
        EXAMPLES
            .iter()
            .map(|(n, _, _)| RobotSpec::Example(n))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_every_example_parses() {
        let mut specs = RobotSpec::examples();
        specs.push(RobotSpec::Chain(4));
        for s in specs {
            assert_eq!(RobotSpec::parse(&s.name()).unwrap(), s);
            assert!(s.robot().unwrap().dof() >= 1);
        }
        for bad in ["chain-0", "chain-x", "nope", ""] {
            assert!(RobotSpec::parse(bad).is_err(), "{bad}");
        }
    }
}
