//! The coefficients of DOP853, copied digit for digit from Hairer & Wanner's `dop853.f`
//! (subroutine `DP86CO`, "version of April 25, 1996, small corrections on March 4, 2002"),
//! as distributed at <http://www.unige.ch/~hairer/software.html> and mirrored in
//! <https://github.com/cpmech/hwode/blob/784b80fe5ed02670bd9f17a73489de42652c38b3/dop853.f>
//! (lines 371–537). The method is
//! Dormand & Prince's 8(5,3) pair, HNW I, II.10 (2nd ed. 1993).
//!
//! Names follow the Fortran: `Cᵢ` nodes, `Aᵢⱼ` the tableau, `Bᵢ` the eighth-order weights,
//! `ERᵢ` = b − b̂ for the fifth-order estimate, `BHHᵢ` the third-order weights on stages 1, 9
//! and 12, `Dᵢⱼ` the dense-output coefficients (rows 4–7 of `CONT`, on stages 1, 6–16).
//! Stage 13 is the FSAL rate f(t₀ + h, y₁); stages 14–16 are evaluated only for the dense
//! output. The literals carry the source's 30 digits (more than an f64 holds) so that they
//! can be compared with it by eye.

#![allow(clippy::excessive_precision)]

use crate::steppers::explicit::Row;

pub(crate) const C2: f64 = 0.526001519587677318785587544488e-01;
pub(crate) const C3: f64 = 0.789002279381515978178381316732e-01;
pub(crate) const C4: f64 = 0.118350341907227396726757197510e+00;
pub(crate) const C5: f64 = 0.281649658092772603273242802490e+00;
pub(crate) const C6: f64 = 0.333333333333333333333333333333e+00;
pub(crate) const C7: f64 = 0.25e+00;
pub(crate) const C8: f64 = 0.307692307692307692307692307692e+00;
pub(crate) const C9: f64 = 0.651282051282051282051282051282e+00;
pub(crate) const C10: f64 = 0.6e+00;
pub(crate) const C11: f64 = 0.857142857142857142857142857142e+00;
pub(crate) const C14: f64 = 0.1e+00;
pub(crate) const C15: f64 = 0.2e+00;
pub(crate) const C16: f64 = 0.777777777777777777777777777778e+00;
pub(crate) const B1: f64 = 5.42937341165687622380535766363e-2;
pub(crate) const B6: f64 = 4.45031289275240888144113950566e0;
pub(crate) const B7: f64 = 1.89151789931450038304281599044e0;
pub(crate) const B8: f64 = -5.8012039600105847814672114227e0;
pub(crate) const B9: f64 = 3.1116436695781989440891606237e-1;
pub(crate) const B10: f64 = -1.52160949662516078556178806805e-1;
pub(crate) const B11: f64 = 2.01365400804030348374776537501e-1;
pub(crate) const B12: f64 = 4.47106157277725905176885569043e-2;
pub(crate) const BHH1: f64 = 0.244094488188976377952755905512e+00;
pub(crate) const BHH2: f64 = 0.733846688281611857341361741547e+00;
pub(crate) const BHH3: f64 = 0.220588235294117647058823529412e-01;
pub(crate) const ER1: f64 = 0.1312004499419488073250102996e-01;
pub(crate) const ER6: f64 = -0.1225156446376204440720569753e+01;
pub(crate) const ER7: f64 = -0.4957589496572501915214079952e+00;
pub(crate) const ER8: f64 = 0.1664377182454986536961530415e+01;
pub(crate) const ER9: f64 = -0.3503288487499736816886487290e+00;
pub(crate) const ER10: f64 = 0.3341791187130174790297318841e+00;
pub(crate) const ER11: f64 = 0.8192320648511571246570742613e-01;
pub(crate) const ER12: f64 = -0.2235530786388629525884427845e-01;
pub(crate) const A21: f64 = 5.26001519587677318785587544488e-2;
pub(crate) const A31: f64 = 1.97250569845378994544595329183e-2;
pub(crate) const A32: f64 = 5.91751709536136983633785987549e-2;
pub(crate) const A41: f64 = 2.95875854768068491816892993775e-2;
pub(crate) const A43: f64 = 8.87627564304205475450678981324e-2;
pub(crate) const A51: f64 = 2.41365134159266685502369798665e-1;
pub(crate) const A53: f64 = -8.84549479328286085344864962717e-1;
pub(crate) const A54: f64 = 9.24834003261792003115737966543e-1;
pub(crate) const A61: f64 = 3.7037037037037037037037037037e-2;
pub(crate) const A64: f64 = 1.70828608729473871279604482173e-1;
pub(crate) const A65: f64 = 1.25467687566822425016691814123e-1;
pub(crate) const A71: f64 = 3.7109375e-2;
pub(crate) const A74: f64 = 1.70252211019544039314978060272e-1;
pub(crate) const A75: f64 = 6.02165389804559606850219397283e-2;
pub(crate) const A76: f64 = -1.7578125e-2;
pub(crate) const A81: f64 = 3.70920001185047927108779319836e-2;
pub(crate) const A84: f64 = 1.70383925712239993810214054705e-1;
pub(crate) const A85: f64 = 1.07262030446373284651809199168e-1;
pub(crate) const A86: f64 = -1.53194377486244017527936158236e-2;
pub(crate) const A87: f64 = 8.27378916381402288758473766002e-3;
pub(crate) const A91: f64 = 6.24110958716075717114429577812e-1;
pub(crate) const A94: f64 = -3.36089262944694129406857109825e0;
pub(crate) const A95: f64 = -8.68219346841726006818189891453e-1;
pub(crate) const A96: f64 = 2.75920996994467083049415600797e1;
pub(crate) const A97: f64 = 2.01540675504778934086186788979e1;
pub(crate) const A98: f64 = -4.34898841810699588477366255144e1;
pub(crate) const A101: f64 = 4.77662536438264365890433908527e-1;
pub(crate) const A104: f64 = -2.48811461997166764192642586468e0;
pub(crate) const A105: f64 = -5.90290826836842996371446475743e-1;
pub(crate) const A106: f64 = 2.12300514481811942347288949897e1;
pub(crate) const A107: f64 = 1.52792336328824235832596922938e1;
pub(crate) const A108: f64 = -3.32882109689848629194453265587e1;
pub(crate) const A109: f64 = -2.03312017085086261358222928593e-2;
pub(crate) const A111: f64 = -9.3714243008598732571704021658e-1;
pub(crate) const A114: f64 = 5.18637242884406370830023853209e0;
pub(crate) const A115: f64 = 1.09143734899672957818500254654e0;
pub(crate) const A116: f64 = -8.14978701074692612513997267357e0;
pub(crate) const A117: f64 = -1.85200656599969598641566180701e1;
pub(crate) const A118: f64 = 2.27394870993505042818970056734e1;
pub(crate) const A119: f64 = 2.49360555267965238987089396762e0;
pub(crate) const A1110: f64 = -3.0467644718982195003823669022e0;
pub(crate) const A121: f64 = 2.27331014751653820792359768449e0;
pub(crate) const A124: f64 = -1.05344954667372501984066689879e1;
pub(crate) const A125: f64 = -2.00087205822486249909675718444e0;
pub(crate) const A126: f64 = -1.79589318631187989172765950534e1;
pub(crate) const A127: f64 = 2.79488845294199600508499808837e1;
pub(crate) const A128: f64 = -2.85899827713502369474065508674e0;
pub(crate) const A129: f64 = -8.87285693353062954433549289258e0;
pub(crate) const A1210: f64 = 1.23605671757943030647266201528e1;
pub(crate) const A1211: f64 = 6.43392746015763530355970484046e-1;
pub(crate) const A141: f64 = 5.61675022830479523392909219681e-2;
pub(crate) const A147: f64 = 2.53500210216624811088794765333e-1;
pub(crate) const A148: f64 = -2.46239037470802489917441475441e-1;
pub(crate) const A149: f64 = -1.24191423263816360469010140626e-1;
pub(crate) const A1410: f64 = 1.5329179827876569731206322685e-1;
pub(crate) const A1411: f64 = 8.20105229563468988491666602057e-3;
pub(crate) const A1412: f64 = 7.56789766054569976138603589584e-3;
pub(crate) const A1413: f64 = -8.298e-3;
pub(crate) const A151: f64 = 3.18346481635021405060768473261e-2;
pub(crate) const A156: f64 = 2.83009096723667755288322961402e-2;
pub(crate) const A157: f64 = 5.35419883074385676223797384372e-2;
pub(crate) const A158: f64 = -5.49237485713909884646569340306e-2;
pub(crate) const A1511: f64 = -1.08347328697249322858509316994e-4;
pub(crate) const A1512: f64 = 3.82571090835658412954920192323e-4;
pub(crate) const A1513: f64 = -3.40465008687404560802977114492e-4;
pub(crate) const A1514: f64 = 1.41312443674632500278074618366e-1;
pub(crate) const A161: f64 = -4.28896301583791923408573538692e-1;
pub(crate) const A166: f64 = -4.69762141536116384314449447206e0;
pub(crate) const A167: f64 = 7.68342119606259904184240953878e0;
pub(crate) const A168: f64 = 4.06898981839711007970213554331e0;
pub(crate) const A169: f64 = 3.56727187455281109270669543021e-1;
pub(crate) const A1613: f64 = -1.39902416515901462129418009734e-3;
pub(crate) const A1614: f64 = 2.9475147891527723389556272149e0;
pub(crate) const A1615: f64 = -9.15095847217987001081870187138e0;
pub(crate) const D41: f64 = -0.84289382761090128651353491142e+01;
pub(crate) const D46: f64 = 0.56671495351937776962531783590e+00;
pub(crate) const D47: f64 = -0.30689499459498916912797304727e+01;
pub(crate) const D48: f64 = 0.23846676565120698287728149680e+01;
pub(crate) const D49: f64 = 0.21170345824450282767155149946e+01;
pub(crate) const D410: f64 = -0.87139158377797299206789907490e+00;
pub(crate) const D411: f64 = 0.22404374302607882758541771650e+01;
pub(crate) const D412: f64 = 0.63157877876946881815570249290e+00;
pub(crate) const D413: f64 = -0.88990336451333310820698117400e-01;
pub(crate) const D414: f64 = 0.18148505520854727256656404962e+02;
pub(crate) const D415: f64 = -0.91946323924783554000451984436e+01;
pub(crate) const D416: f64 = -0.44360363875948939664310572000e+01;
pub(crate) const D51: f64 = 0.10427508642579134603413151009e+02;
pub(crate) const D56: f64 = 0.24228349177525818288430175319e+03;
pub(crate) const D57: f64 = 0.16520045171727028198505394887e+03;
pub(crate) const D58: f64 = -0.37454675472269020279518312152e+03;
pub(crate) const D59: f64 = -0.22113666853125306036270938578e+02;
pub(crate) const D510: f64 = 0.77334326684722638389603898808e+01;
pub(crate) const D511: f64 = -0.30674084731089398182061213626e+02;
pub(crate) const D512: f64 = -0.93321305264302278729567221706e+01;
pub(crate) const D513: f64 = 0.15697238121770843886131091075e+02;
pub(crate) const D514: f64 = -0.31139403219565177677282850411e+02;
pub(crate) const D515: f64 = -0.93529243588444783865713862664e+01;
pub(crate) const D516: f64 = 0.35816841486394083752465898540e+02;
pub(crate) const D61: f64 = 0.19985053242002433820987653617e+02;
pub(crate) const D66: f64 = -0.38703730874935176555105901742e+03;
pub(crate) const D67: f64 = -0.18917813819516756882830838328e+03;
pub(crate) const D68: f64 = 0.52780815920542364900561016686e+03;
pub(crate) const D69: f64 = -0.11573902539959630126141871134e+02;
pub(crate) const D610: f64 = 0.68812326946963000169666922661e+01;
pub(crate) const D611: f64 = -0.10006050966910838403183860980e+01;
pub(crate) const D612: f64 = 0.77771377980534432092869265740e+00;
pub(crate) const D613: f64 = -0.27782057523535084065932004339e+01;
pub(crate) const D614: f64 = -0.60196695231264120758267380846e+02;
pub(crate) const D615: f64 = 0.84320405506677161018159903784e+02;
pub(crate) const D616: f64 = 0.11992291136182789328035130030e+02;
pub(crate) const D71: f64 = -0.25693933462703749003312586129e+02;
pub(crate) const D76: f64 = -0.15418974869023643374053993627e+03;
pub(crate) const D77: f64 = -0.23152937917604549567536039109e+03;
pub(crate) const D78: f64 = 0.35763911791061412378285349910e+03;
pub(crate) const D79: f64 = 0.93405324183624310003907691704e+02;
pub(crate) const D710: f64 = -0.37458323136451633156875139351e+02;
pub(crate) const D711: f64 = 0.10409964950896230045147246184e+03;
pub(crate) const D712: f64 = 0.29840293426660503123344363579e+02;
pub(crate) const D713: f64 = -0.43533456590011143754432175058e+02;
pub(crate) const D714: f64 = 0.96324553959188282948394950600e+02;
pub(crate) const D715: f64 = -0.39177261675615439165231486172e+02;
pub(crate) const D716: f64 = -0.14972683625798562581422125276e+03;

/// The rows d₄…d₇ of the dense output (`CONT(4…7)` of `dop853.f`), each over the stages
/// k₁, k₆…k₁₆ in that order.
pub(crate) const DENSE_ROWS: [[f64; 12]; 4] = [
    [
        D41, D46, D47, D48, D49, D410, D411, D412, D413, D414, D415, D416,
    ],
    [
        D51, D56, D57, D58, D59, D510, D511, D512, D513, D514, D515, D516,
    ],
    [
        D61, D66, D67, D68, D69, D610, D611, D612, D613, D614, D615, D616,
    ],
    [
        D71, D76, D77, D78, D79, D710, D711, D712, D713, D714, D715, D716,
    ],
];

/// The explicit stages 2–12 as a step evaluates them, in order: the node cᵢ and the
/// non-zero aᵢⱼ as (j, aᵢⱼ), stages numbered from 1 as in the Fortran.
pub(crate) const STAGE_ROWS: [(f64, &[(usize, f64)]); 11] = [
    (C2, &[(1, A21)]),
    (C3, &[(1, A31), (2, A32)]),
    (C4, &[(1, A41), (3, A43)]),
    (C5, &[(1, A51), (3, A53), (4, A54)]),
    (C6, &[(1, A61), (4, A64), (5, A65)]),
    (C7, &[(1, A71), (4, A74), (5, A75), (6, A76)]),
    (C8, &[(1, A81), (4, A84), (5, A85), (6, A86), (7, A87)]),
    (
        C9,
        &[(1, A91), (4, A94), (5, A95), (6, A96), (7, A97), (8, A98)],
    ),
    (
        C10,
        &[
            (1, A101),
            (4, A104),
            (5, A105),
            (6, A106),
            (7, A107),
            (8, A108),
            (9, A109),
        ],
    ),
    (
        C11,
        &[
            (1, A111),
            (4, A114),
            (5, A115),
            (6, A116),
            (7, A117),
            (8, A118),
            (9, A119),
            (10, A1110),
        ],
    ),
    (
        1.0,
        &[
            (1, A121),
            (4, A124),
            (5, A125),
            (6, A126),
            (7, A127),
            (8, A128),
            (9, A129),
            (10, A1210),
            (11, A1211),
        ],
    ),
];

/// b, the eighth-order weights, as the explicit core takes them (stages 2–5 weigh 0).
pub(crate) const WEIGHTS: Row = &[
    (1, B1),
    (6, B6),
    (7, B7),
    (8, B8),
    (9, B9),
    (10, B10),
    (11, B11),
    (12, B12),
];

/// The fifth-order error estimate's weights, `er` of `dop853.f` (b − er has order 5).
pub(crate) const ERROR_WEIGHTS: Row = &[
    (1, ER1),
    (6, ER6),
    (7, ER7),
    (8, ER8),
    (9, ER9),
    (10, ER10),
    (11, ER11),
    (12, ER12),
];

#[cfg(test)]
mod tests {
    //! The table against the order conditions it claims, in f64 (the decimals are not
    //! rationals we could recover): each defect is compared with a bound a few times the
    //! largest one measured, stated where it is asserted.
    use super::*;
    use crate::steppers::order_conditions::{defects, stage_weights, trees};

    const STAGES: usize = 16;

    /// The extended tableau: the twelve stages of a step, stage 13 = f(t₀ + h, y₁) (its
    /// row is b) and the three stages of the dense output.
    fn tableau() -> Vec<Vec<f64>> {
        let mut a = vec![vec![0.0; STAGES]; STAGES];
        let mut set = |row: usize, entries: &[(usize, f64)]| {
            for &(column, value) in entries {
                a[row - 1][column - 1] = value;
            }
        };
        // Rows 2–12 are the table the step runs.
        for (row, (_, entries)) in STAGE_ROWS.iter().enumerate() {
            set(row + 2, entries);
        }
        let b = weights();
        for (column, value) in b.iter().enumerate() {
            a[12][column] = *value;
        }
        let mut set = |row: usize, entries: &[(usize, f64)]| {
            for &(column, value) in entries {
                a[row - 1][column - 1] = value;
            }
        };
        set(
            14,
            &[
                (1, A141),
                (7, A147),
                (8, A148),
                (9, A149),
                (10, A1410),
                (11, A1411),
                (12, A1412),
                (13, A1413),
            ],
        );
        set(
            15,
            &[
                (1, A151),
                (6, A156),
                (7, A157),
                (8, A158),
                (11, A1511),
                (12, A1512),
                (13, A1513),
                (14, A1514),
            ],
        );
        set(
            16,
            &[
                (1, A161),
                (6, A166),
                (7, A167),
                (8, A168),
                (9, A169),
                (13, A1613),
                (14, A1614),
                (15, A1615),
            ],
        );
        a
    }

    /// A vector over the 16 stages from (stage, value) pairs.
    fn on_stages(entries: &[(usize, f64)]) -> Vec<f64> {
        let mut v = vec![0.0; STAGES];
        for &(stage, value) in entries {
            v[stage - 1] = value;
        }
        v
    }

    /// The eighth-order weights b.
    fn weights() -> Vec<f64> {
        on_stages(WEIGHTS)
    }

    /// The largest |defect| over the trees of each order 1..=max.
    fn worst_by_order(b: &[f64], a: &[Vec<f64>], max: usize, theta: f64) -> Vec<f64> {
        let all = trees(max);
        let defects = defects(b, &stage_weights(a, &all), &all, theta);
        (1..=max)
            .map(|order| {
                all.iter()
                    .zip(&defects)
                    .filter(|(tree, _)| tree.order == order)
                    .map(|(_, d)| d.abs())
                    .fold(0.0, f64::max)
            })
            .collect()
    }

    #[test]
    fn the_nodes_are_the_row_sums() {
        let a = tableau();
        // Nodes 2–12 as the step uses them (from `STAGE_ROWS`).
        let mut nodes = [0.0; STAGES];
        for (row, (c, _)) in STAGE_ROWS.iter().enumerate() {
            nodes[row + 1] = *c;
        }
        (nodes[12], nodes[13], nodes[14], nodes[15]) = (1.0, C14, C15, C16);
        let worst = a
            .iter()
            .zip(nodes)
            .map(|(row, c)| (row.iter().sum::<f64>() - c).abs())
            .fold(0.0, f64::max);
        eprintln!("worst row sum − c: {worst:e}");
        // Measured: 6.1e-15 (entries up to 43 in size); bound ~3× that.
        assert!(worst < 2e-14, "{worst:e}");
    }

    #[test]
    fn the_weights_have_order_eight() {
        let worst = worst_by_order(&weights(), &tableau(), 9, 1.0);
        eprintln!("b: worst defect by order {worst:?}");
        // Measured: at most 2.2e-15 to order 8 (bound ~20×); the ninth fails by 2.7e-5.
        assert!(worst[..8].iter().all(|&d| d < 5e-14), "{worst:?}");
        assert!(worst[8] > 1e-6, "{worst:?}");
    }

    #[test]
    fn the_embedded_estimates_have_orders_five_and_three() {
        let a = tableau();
        let er = on_stages(ERROR_WEIGHTS);
        let fifth: Vec<f64> = weights().iter().zip(&er).map(|(b, e)| b - e).collect();
        let worst = worst_by_order(&fifth, &a, 6, 1.0);
        eprintln!("b − er: worst defect by order {worst:?}");
        // Measured: at most 5.0e-15 to order 5; the sixth fails by 4.5e-4.
        assert!(worst[..5].iter().all(|&d| d < 5e-14), "{worst:?}");
        assert!(worst[5] > 1e-6, "{worst:?}");
        let third = on_stages(&[(1, BHH1), (9, BHH2), (12, BHH3)]);
        let worst = worst_by_order(&third, &a, 4, 1.0);
        eprintln!("bhh: worst defect by order {worst:?}");
        // Measured: at most 3.6e-15 to order 3; the fourth fails by 2.5e-2.
        assert!(worst[..3].iter().all(|&d| d < 5e-14), "{worst:?}");
        assert!(worst[3] > 1e-6, "{worst:?}");
    }

    /// The weights b(θ) of `CONTD8`, built as the stepper builds `CONT` with h = 1,
    /// y₀ = 0 and the stages kⱼ = eⱼ.
    fn continuous_weights(theta: f64) -> Vec<f64> {
        let b = weights();
        let unit = |stage: usize| on_stages(&[(stage, 1.0)]);
        let stages = [1, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16];
        let row = |d: [f64; 12]| {
            let pairs: Vec<(usize, f64)> = stages.iter().copied().zip(d).collect();
            on_stages(&pairs)
        };
        let first: Vec<f64> = unit(1).iter().zip(&b).map(|(e, b)| e - b).collect();
        let third: Vec<f64> = (0..STAGES).map(|j| b[j] - unit(13)[j] - first[j]).collect();
        let c = [
            b.clone(),
            first,
            third,
            row(DENSE_ROWS[0]),
            row(DENSE_ROWS[1]),
            row(DENSE_ROWS[2]),
            row(DENSE_ROWS[3]),
        ];
        let (s, s1) = (theta, 1.0 - theta);
        (0..STAGES)
            .map(|j| {
                let inner = c[3][j] + s * (c[4][j] + s1 * (c[5][j] + s * c[6][j]));
                s * (c[0][j] + s1 * (c[1][j] + s * (c[2][j] + s1 * inner)))
            })
            .collect()
    }

    #[test]
    fn the_dense_output_has_order_seven() {
        let a = tableau();
        for theta in [0.1, 0.5, 0.77] {
            let worst = worst_by_order(&continuous_weights(theta), &a, 8, theta);
            eprintln!("b({theta}): worst defect by order {worst:?}");
            // Measured: at most 2.8e-15 to order 7; the eighth fails by ≥ 7.5e-6.
            assert!(
                worst[..7].iter().all(|&d| d < 5e-14),
                "θ = {theta}: {worst:?}"
            );
            assert!(worst[7] > 1e-7, "θ = {theta}: {worst:?}");
        }
    }
}
