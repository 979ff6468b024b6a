//! The test systems, in the DSL.
#![allow(dead_code)]

/// The paper's sled, paper form (docs/dsl.md#the-sled-both-ways), with the checks of eqs. 21–24.
pub const SLED_PAPER: &str = "
coordinates x
mass m = m0 + c*x
lagrangian 1/2*m*x'^2 + m*g*x*sin(theta)
force x: -f_d*m*g*cos(theta)
impact x: -c*x'^2
check p_x = m*x'
check H = p_x^2/(2*m) - m*g*x*sin(theta)
check x'' = g*sin(theta) - f_d*g*cos(theta) - c*x'^2/m
";

/// The paper's sled, body form: R2 derived from the inflow of snow at rest.
pub const SLED_BODY: &str = "
coordinates x
mass m = m0 + c*x
body sled: mass m, position [x]
potential -m*g*x*sin(theta)
force sled: [-f_d*m*g*cos(theta)]
inflow sled: velocity [0]
check p_x = m*x'
check H = p_x^2/(2*m) - m*g*x*sin(theta)
check R2_x = -c*x'^2
check x'' = g*sin(theta) - f_d*g*cos(theta) - c*x'^2/m
";

/// A vertical rocket burning at a constant rate.
pub const ROCKET: &str = "
coordinates y
mass m: state, rate -mu
body rocket: mass m, position [y]
potential m*g*y
outflow rocket: rate mu, relative_velocity [-u_e]
";

/// A constant-mass double pendulum (angles a, b from the downward vertical).
pub const DOUBLE_PENDULUM: &str = "
coordinates a, b
mass m1 = M1
mass m2 = M2
body bob1: mass m1, position [l1*sin(a), -l1*cos(a)]
body bob2: mass m2, position [l1*sin(a) + l2*sin(b), -l1*cos(a) - l2*cos(b)]
potential m1*g*(-l1*cos(a)) + m2*g*(-l1*cos(a) - l2*cos(b))
";

/// A leaking spring pendulum in polar coordinates: a state mass that loses mass at a rate
/// proportional to itself, expelled backwards along the spring.
pub const LEAKING_SPRING_PENDULUM: &str = "
coordinates r, th
mass m: state, rate -k*m
body bob: mass m, position [r*sin(th), -r*cos(th)]
potential -m*g*r*cos(th) + 1/2*K*(r - l0)^2
outflow bob: relative_velocity [-u*sin(th), u*cos(th)]
";

/// A bead on a rotating rod (explicit time dependence) that accretes mass from rest, with a
/// mass law in both q and t.
pub const ACCRETING_BEAD: &str = "
coordinates s
let w = omega*t
mass m = m0 + c*s^2 + k*t
body bead: mass m, position [s*cos(w), s*sin(w)]
inflow bead: velocity [0, 0]
force s: -b*s'
";

/// A three-coordinate variable-mass system, past the symbolic-inverse threshold: a rocket
/// sled on a swinging arm in a plane, with a state mass.
pub const THREE_DOF: &str = "
coordinates x, y, th
mass m: state, rate -mu
mass M = M0
inertia J = J0
body hull: mass M, position [x, y]
body tank: mass m, position [x + l*cos(th), y + l*sin(th)]
kinetic 1/2*J*th'^2
potential M*g*y + m*g*(y + l*sin(th)) + 1/2*K*(x^2 + y^2)
outflow tank: rate mu, relative_velocity [-u_e*cos(th), -u_e*sin(th)]
";

/// Every system above with a name.
pub const ALL: &[(&str, &str)] = &[
    ("sled (paper form)", SLED_PAPER),
    ("sled (body form)", SLED_BODY),
    ("rocket", ROCKET),
    ("double pendulum", DOUBLE_PENDULUM),
    ("leaking spring pendulum", LEAKING_SPRING_PENDULUM),
    ("accreting bead", ACCRETING_BEAD),
    ("three dof", THREE_DOF),
];
