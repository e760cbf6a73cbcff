//! What the SINUMERIK tests share: the default machine on the SINUMERIK profile and a tool edge
//! of its tool table.

use vcnc::machine::ToolEdge;
use vcnc::{Machine, ProfileName};

/// The default machine on the 840D profile.
pub fn machine() -> Machine {
    Machine::default()
        .with_profile(ProfileName::Sinumerik)
        .expect("the default machine fits the SINUMERIK profile")
}

/// Edge `d` of milling tool `t` (type 120, four teeth) called `name`, with length L1 and radius.
pub fn mill(t: u32, name: &str, d: u32, length: f64, radius: f64) -> ToolEdge {
    ToolEdge {
        t,
        name: Some(name.into()),
        d,
        tool_type: 120,
        length,
        length2: 0.0,
        length3: 0.0,
        radius,
        teeth: Some(4),
    }
}
