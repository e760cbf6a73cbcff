//! G16/G15 polar coordinate command (spec iso-syntec-milling.md 1.14): the manual's three holes
//! (there drilled with G81, here reached with G01), incremental angles and radii, words left out.

use crate::common::check;

#[test]
fn three_holes_on_a_circle_of_100() {
    // Example 1 (file 20-g16-polar-absolute.nc) positions: angles 90, 210 and 330 degrees.
    check(
        "G17 G90 G16\nG1 X100. Y90. F600.\nY210.\nY330.\nG15\nM30",
        "
        line X0 Y100 Z0 F600
        line X-86.6025 Y-50 Z0 F600
        line X86.6025 Y-50 Z0 F600
        end M30",
    );
}

#[test]
fn in_g91_angle_and_radius_add_to_the_previous_point() {
    // Example 2's intent (file 21-g16-polar-incremental.nc): +120 degrees per block.
    check(
        "G17 G90 G16\nG1 X100. Y90. F600.\nG91 Y120.\nY120.\nX-50.\nG15\nM30",
        "
        line X0 Y100 Z0 F600
        line X-86.6025 Y-50 Z0 F600
        line X86.6025 Y-50 Z0 F600
        line X43.3013 Y-25 Z0 F600
        end M30",
    );
}

#[test]
fn polar_values_start_from_the_current_position_and_g15_returns_to_cartesian() {
    // At (0,20): radius 20, angle 90; Y180 keeps the radius.
    check(
        "G90 G0 X0 Y20.\nG16\nG1 Y180. F100.\nG15\nX5.\nM30",
        "
        rapid X0 Y20 Z0
        line X-20 Y0 Z0 F100
        line X5 Y0 Z0 F100
        end M30",
    );
}

#[test]
fn other_axes_and_arc_words_are_not_converted() {
    // Z stays Cartesian; the arc's end is polar, its R is a radius.
    check(
        "G90 G0 X10. Y0\nG16\nG1 Z-1. F100.\nG3 X10. Y90. R10.\nG15\nM30",
        "
        rapid X10 Y0 Z0
        line X10 Y0 Z-1 F100
        arc ccw xy X0 Y10 Z-1 C(0,0,-1) F100
        end M30",
    );
}
