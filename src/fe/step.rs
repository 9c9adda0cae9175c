//! Analysis steps and what they hold: boundary conditions and loads, on the model's named
//! node sets, element sets and surfaces.

use glam::DVec3;
use serde::Serialize;

/// The procedure of a step.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub enum Analysis {
    /// Linear static (`*STATIC`, SOL 101).
    Static,
    /// Natural frequencies (`*FREQUENCY`, SOL 103): the number of modes.
    Frequency {
        /// Modes to extract.
        modes: u32,
    },
    /// Steady-state heat transfer (`*HEAT TRANSFER, STEADY STATE`).
    Heat,
}

/// A boundary condition.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub enum Bc {
    /// Degrees of freedom 1..=3 (translations) held at zero on a node set.
    Fixed {
        /// The node set.
        nodes: String,
        /// The degrees of freedom, 1 to 3.
        dofs: Vec<u8>,
    },
    /// A prescribed displacement of one degree of freedom on a node set.
    Displacement {
        /// The node set.
        nodes: String,
        /// The degree of freedom, 1 to 3.
        dof: u8,
        /// The value.
        value: f64,
    },
    /// A prescribed temperature (degree of freedom 11) on a node set.
    Temperature {
        /// The node set.
        nodes: String,
        /// The value.
        value: f64,
    },
}

/// A load.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub enum Load {
    /// Forces at nodes (a total force spread over a surface as consistent nodal loads,
    /// [`super::loads::consistent_forces`]).
    Nodal {
        /// What it came from (the selector), for comments and reports.
        name: String,
        /// The surface it was spread over.
        surface: String,
        /// The total asked for.
        total: DVec3,
        /// Node and force, nodes in increasing order.
        forces: Vec<(u32, DVec3)>,
    },
    /// A pressure on a surface, positive into the element (`*DSLOAD ... P`, `PLOAD4`).
    Pressure {
        /// The surface.
        surface: String,
        /// The pressure.
        value: f64,
    },
    /// Gravity (an acceleration) on an element set.
    Gravity {
        /// The element set.
        elements: String,
        /// The acceleration vector (magnitude × direction).
        acceleration: DVec3,
    },
    /// A heat flux into a surface.
    HeatFlux {
        /// The surface.
        surface: String,
        /// Flux per area.
        value: f64,
    },
    /// Convection on a surface: film coefficient and sink temperature.
    Film {
        /// The surface.
        surface: String,
        /// The film coefficient.
        coefficient: f64,
        /// The sink temperature.
        sink: f64,
    },
}

/// A step.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Step {
    /// Its name (for comments and reports).
    pub name: String,
    /// The procedure.
    pub analysis: Analysis,
    /// Boundary conditions.
    pub bcs: Vec<Bc>,
    /// Loads.
    pub loads: Vec<Load>,
}
