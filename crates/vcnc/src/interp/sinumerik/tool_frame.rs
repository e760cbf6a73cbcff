//! Frames along the tool's orientation, TOFRAME and TOROT with their X, Y and Z forms (PGsl 4.8,
//! L9246-9340): the programmable frame turned so that one of its axes (Z; Y for TOFRAMEY and
//! TOROTY; X for TOFRAMEX and TOROTX) points along the tool, from the tip towards the spindle.
//!
//! The tool's direction comes from the machine file's kinematics at the rotary axes' present
//! positions, seen in the coordinates the programmable frame turns (a CYCLE800 swivel frame in
//! force taken out); a machine without kinematics holds its tool along Z. About that axis the
//! frame is turned so that its next axis lies in the plane of the old Z and X axes (MD21110
//! X_AXES_IN_OLD_X_Z_PLANE set: **choice**, the control's other setting leaves the turn the
//! kinematics happen to make). With the tool along Z, TOFRAME turns nothing.

use crate::interp::kernel::Kernel;
use crate::kinematics::Vec3;

/// Which of the frame's axes points along the tool.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Applicate {
    X,
    Y,
    Z,
}

/// The tool's direction in the coordinates the programmable frame turns: a unit vector.
pub(super) fn tool_direction(kernel: &Kernel) -> Vec3 {
    let state = kernel.state();
    let Some(kinematics) = state.setup.machine().kinematics.as_ref() else {
        return [0.0, 0.0, 1.0];
    };
    let axis = kinematics.forward(&kernel.position().0, 0.0).axis;
    match state.frames.swivel() {
        // The swivel frame maps its coordinates onto the machine's by its linear part L: a
        // direction seen in them is L^T d (L is a rotation).
        Some(swivel) => {
            let l = swivel.linear();
            std::array::from_fn(|i| (0..3).map(|k| l[k][i] * axis[k]).sum())
        }
        None => axis,
    }
}

/// The rotation (columns: the frame's X, Y and Z axes in the old coordinates) whose `applicate`
/// axis is `direction`, the axis after it in X Y Z order lying in the old Z-X plane.
pub(super) fn rotation(direction: Vec3, applicate: Applicate) -> [[f64; 3]; 3] {
    let length = direction.iter().map(|v| v * v).sum::<f64>().sqrt();
    let z = if length > 1e-12 {
        direction.map(|v| v / length)
    } else {
        [0.0, 0.0, 1.0]
    };
    // x in span(old X, old Z), square to z: (z_z, 0, -z_x), pointing along old X; along old Y
    // the tool leaves the plane no direction, and old X is kept.
    let across = z[2].hypot(z[0]);
    let x = if across > 1e-12 {
        [z[2] / across, 0.0, -z[0] / across]
    } else {
        [1.0, 0.0, 0.0]
    };
    let y = [
        z[1] * x[2] - z[2] * x[1],
        z[2] * x[0] - z[0] * x[2],
        z[0] * x[1] - z[1] * x[0],
    ];
    // The table of PGsl 4.8: applicate Y takes Z as abscissa and X as ordinate, applicate X
    // takes Y and Z: the triple turned cyclically, so the frame stays right-handed.
    let (fx, fy, fz) = match applicate {
        Applicate::Z => (x, y, z),
        Applicate::Y => (y, z, x),
        Applicate::X => (z, x, y),
    };
    std::array::from_fn(|row| [fx[row], fy[row], fz[row]])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn column(m: &[[f64; 3]; 3], c: usize) -> Vec3 {
        [m[0][c], m[1][c], m[2][c]]
    }

    fn close(a: Vec3, b: Vec3) -> bool {
        a.iter().zip(b).all(|(p, q)| (p - q).abs() < 1e-12)
    }

    /// A vertical tool: TOFRAME is the identity (the manual's example, PGsl 4.8); TOFRAMEY puts
    /// the frame's Y along old Z, its Z (the abscissa of the table) along old X.
    #[test]
    fn a_vertical_tool_gives_no_turn_for_toframe() {
        let identity = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        assert_eq!(rotation([0.0, 0.0, 1.0], Applicate::Z), identity);
        let y = rotation([0.0, 0.0, 1.0], Applicate::Y);
        assert!(close(column(&y, 1), [0.0, 0.0, 1.0]));
        assert!(close(column(&y, 2), [1.0, 0.0, 0.0]));
        assert!(close(column(&y, 0), [0.0, 1.0, 0.0]));
    }

    /// A tool tilted 30 degrees about Y (B30 on a head): direction (sin 30, 0, cos 30) =
    /// (0.5, 0, 0.866); the frame's X is (cos 30, 0, -sin 30), in the old Z-X plane, its Y the
    /// old Y: the same turn as ROT Y30.
    #[test]
    fn a_tool_tilted_about_y_gives_the_turn_about_y() {
        let (s, c) = 30f64.to_radians().sin_cos();
        let m = rotation([s, 0.0, c], Applicate::Z);
        assert!(close(column(&m, 0), [c, 0.0, -s]));
        assert!(close(column(&m, 1), [0.0, 1.0, 0.0]));
        assert!(close(column(&m, 2), [s, 0.0, c]));
    }

    proptest::proptest! {
        /// Every result is a rotation (orthonormal, determinant 1) with the asked axis along
        /// the direction and the next axis in the old Z-X plane.
        #[test]
        fn the_frame_is_a_rotation_with_its_axis_along_the_tool(
            d in proptest::array::uniform3(-1.0f64..1.0),
            which in 0usize..3,
        ) {
            let n = d.iter().map(|v| v * v).sum::<f64>().sqrt();
            proptest::prop_assume!(n > 1e-3 && d[0].hypot(d[2]) > 1e-3);
            let applicate = [Applicate::X, Applicate::Y, Applicate::Z][which];
            let m = rotation(d, applicate);
            for i in 0..3 {
                for j in 0..3 {
                    let dot: f64 = (0..3).map(|k| m[k][i] * m[k][j]).sum();
                    proptest::prop_assert!((dot - f64::from(u8::from(i == j))).abs() < 1e-9);
                }
            }
            let det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
                - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
                + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
            proptest::prop_assert!((det - 1.0).abs() < 1e-9);
            let along = column(&m, which);
            proptest::prop_assert!(along.iter().zip(d).all(|(a, b)| (a - b / n).abs() < 1e-9));
            let next = column(&m, (which + 1) % 3);
            proptest::prop_assert!(next[1].abs() < 1e-9);
        }
    }
}
