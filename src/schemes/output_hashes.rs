//! Output fingerprints of the level schemes, recorded with the builder that
//! went through `Mesh::from_corner_twins` (issue 19, item 1): the direct
//! column fills must give bit-identical meshes, i.e. the same positions, the
//! same vertex, half-edge and face order, the same `v_out` and `f_start`
//! choices, and the same exports (sizes, indices, corner twins).
//!
//! `TOPOMESH_PRINT_HASHES=1 cargo test output_hashes -- --nocapture` prints
//! the table instead of checking it (for a scheme whose output changes on
//! purpose).

use super::hosts::test_meshes as tm;
use super::level::{Level, Request};
use crate::mesh::Mesh;
use crate::primitives;

/// FNV-1a over bytes, 64-bit: deterministic across runs and platforms.
struct Fnv(u64);
impl Fnv {
    fn new() -> Fnv {
        Fnv(0xcbf2_9ce4_8422_2325)
    }
    fn bytes(&mut self, b: &[u8]) {
        for &x in b {
            self.0 ^= x as u64;
            self.0 = self.0.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
    fn u32s(&mut self, s: &[u32]) {
        self.bytes(&(s.len() as u64).to_le_bytes());
        for &x in s {
            self.bytes(&x.to_le_bytes());
        }
    }
}

/// Every stored column and every export of `m`.
pub(crate) fn mesh_hash(m: &Mesh) -> u64 {
    let mut h = Fnv::new();
    for p in &m.pos {
        for c in [p.x, p.y, p.z] {
            h.bytes(&c.to_bits().to_le_bytes());
        }
    }
    for col in [&m.v_out, &m.he_next, &m.he_prev, &m.he_vert, &m.he_face, &m.f_start] {
        h.u32s(col);
    }
    h.bytes(&m.f_hole.iter().map(|&b| b as u8).collect::<Vec<_>>());
    let p = m.to_polygons();
    h.u32s(&p.sizes);
    h.u32s(&p.indices);
    for t in m.corner_twins() {
        h.bytes(&t.to_le_bytes());
    }
    h.0
}

/// The mesh, and with a full request the origins too (they come from the
/// hosts' side maps).
fn level_hash(lv: &Level) -> u64 {
    let mut h = Fnv::new();
    h.bytes(&mesh_hash(&lv.mesh).to_le_bytes());
    if let Some(o) = &lv.origins {
        for (k, i) in [(&o.vertex_kind, &o.vertex), (&o.edge_kind, &o.edge), (&o.face_kind, &o.face)] {
            h.bytes(k);
            h.u32s(i);
        }
    }
    h.0
}

type LevelFn = fn(&Mesh, &Request) -> crate::error::Result<Level>;

fn schemes() -> Vec<(&'static str, LevelFn)> {
    use super::*;
    vec![
        ("catmull_clark", catmull_clark::catmull_clark_level),
        ("loop", loop_subdivision::loop_level),
        ("midpoint", midpoint::midpoint_level),
        ("doo_sabin", doo_sabin::doo_sabin_level),
        ("dual", dual::dual_level),
        ("sqrt3", sqrt3::sqrt3_level),
        ("simplest", simplest::simplest_level),
        ("honeycomb", |m, r| honeycomb::honeycomb_level(m, 0.5, None, r)),
        ("vertex_truncation", |m, r| {
            vertex_truncation::vertex_truncation_level(m, vertex_truncation::Truncation::Chaikin, r)
        }),
    ]
}

fn inputs() -> Vec<(&'static str, Mesh)> {
    vec![
        ("torus", primitives::torus(8, 5, 1.0, 0.4).unwrap()),
        ("genus2", primitives::genus_surface(2).unwrap()),
        ("open_grid", tm::open_grid(4)),
        ("ico_two_holes", tm::icosahedron_with_two_holes()),
        ("self_loop", tm::cube_with_self_loop()),
        ("two_gon", tm::cube_with_two_gon()),
        ("one_two_gon", tm::one_gon_two_gon_cube()),
        ("handle_loop", tm::cube_with_handle_loop()),
        ("point_sphere", tm::with_point_sphere()),
    ]
}

/// `scheme/input/run` → hash, for every scheme, input and run: `plain1`,
/// `plain2` (two levels, the second with `level = 1`) and `full1` (stencils
/// and origins requested). A scheme refusing an input is recorded as 0.
fn table() -> Vec<(String, u64)> {
    let mut out = Vec::new();
    for (s, f) in schemes() {
        for (i, m) in inputs() {
            let plain = Request::plain();
            let l1 = f(&m, &plain);
            out.push((format!("{s}/{i}/plain1"), l1.as_ref().map(level_hash).unwrap_or(0)));
            let l2 = l1.ok().and_then(|l| f(&l.mesh, &Request { level: 1, ..Request::plain() }).ok());
            out.push((format!("{s}/{i}/plain2"), l2.as_ref().map(level_hash).unwrap_or(0)));
            let full = tm::full_request();
            out.push((format!("{s}/{i}/full1"), f(&m, &full).as_ref().map(level_hash).unwrap_or(0)));
        }
    }
    out
}

/// A level keeps its stencils only when asked for, on open meshes too
/// (issue 19: the rows of an open level cost several times its output;
/// their positions are applied row by row instead, the same bits, which
/// [`scheme_outputs_are_unchanged`] checks).
#[test]
fn levels_store_no_stencils_unless_asked() {
    let mut checked = 0;
    for (s, f) in schemes() {
        for (i, m) in inputs() {
            let Ok(lv) = f(&m, &Request::plain()) else { continue };
            assert!(lv.stencils.is_none(), "{s}/{i}: stencils kept without a request");
            let asked = f(&m, &Request { stencils: true, ..Request::plain() }).unwrap();
            assert!(asked.stencils.is_some(), "{s}/{i}: stencils asked for");
            checked += m.n_holes().min(1);
        }
    }
    assert!(checked >= 2 * schemes().len(), "open inputs were not exercised: {checked}");
}

#[test]
fn scheme_outputs_are_unchanged() {
    let got = table();
    if check_recorded(&got, EXPECTED) {
        // the table must exercise real outputs, not only refusals
        assert!(got.iter().filter(|(_, h)| *h != 0).count() > got.len() * 3 / 4);
    }
}

/// Compares `got` with the `recorded` hashes and fails listing every
/// changed or unrecorded entry; with `TOPOMESH_PRINT_HASHES` set it prints
/// `got` as a table to paste instead and returns false (nothing compared).
pub(crate) fn check_recorded(got: &[(String, u64)], recorded: &[(&str, u64)]) -> bool {
    if std::env::var_os("TOPOMESH_PRINT_HASHES").is_some() {
        for (k, h) in got {
            println!("    (\"{k}\", 0x{h:016x}),");
        }
        return false;
    }
    let want: std::collections::HashMap<&str, u64> = recorded.iter().copied().collect();
    let mut bad = Vec::new();
    for (k, h) in got {
        match want.get(k.as_str()) {
            Some(w) if w == h => {}
            Some(w) => bad.push(format!("{k}: 0x{h:016x}, recorded 0x{w:016x}")),
            None => bad.push(format!("{k}: not recorded")),
        }
    }
    assert!(bad.is_empty(), "{} outputs changed:\n{}", bad.len(), bad.join("\n"));
    true
}

/// Recorded with the `from_corner_twins` builders (main at 4dd049a).
const EXPECTED: &[(&str, u64)] = &[
    ("catmull_clark/torus/plain1", 0xbdc0cb14ecf6f5a0),
    ("catmull_clark/torus/plain2", 0x7642d18293740b4f),
    ("catmull_clark/torus/full1", 0x80d68b210b1bd7db),
    ("catmull_clark/genus2/plain1", 0x01e2216653a7601e),
    ("catmull_clark/genus2/plain2", 0xdea33a7812ce3459),
    ("catmull_clark/genus2/full1", 0x64c49b5fc3f5ef8c),
    ("catmull_clark/open_grid/plain1", 0x0a143d17237d21e0),
    ("catmull_clark/open_grid/plain2", 0x9e8fcc5d6dfd15ee),
    ("catmull_clark/open_grid/full1", 0x1e4b1b923b92b8bc),
    ("catmull_clark/ico_two_holes/plain1", 0x9352ad056cdfdc2b),
    ("catmull_clark/ico_two_holes/plain2", 0xadc8f900334489ed),
    ("catmull_clark/ico_two_holes/full1", 0xbed070146ab323ba),
    ("catmull_clark/self_loop/plain1", 0x7a656f112e561141),
    ("catmull_clark/self_loop/plain2", 0x7d18e8a6772505e0),
    ("catmull_clark/self_loop/full1", 0xe4753bdd6f5c8463),
    ("catmull_clark/two_gon/plain1", 0xea0744c6048f0fe6),
    ("catmull_clark/two_gon/plain2", 0x7062dddc7b3e9f05),
    ("catmull_clark/two_gon/full1", 0x475c523b4620c05e),
    ("catmull_clark/one_two_gon/plain1", 0x7a1eb5ad77cfd69a),
    ("catmull_clark/one_two_gon/plain2", 0xb1a9fb874b361806),
    ("catmull_clark/one_two_gon/full1", 0xeacb94e607257d7d),
    ("catmull_clark/handle_loop/plain1", 0x26db5a91e2cb4a88),
    ("catmull_clark/handle_loop/plain2", 0x3a39c17c8952cad6),
    ("catmull_clark/handle_loop/full1", 0xa44ee73f5056bd45),
    ("catmull_clark/point_sphere/plain1", 0x26e526eb7c760c42),
    ("catmull_clark/point_sphere/plain2", 0x915dfd1fef3294d1),
    ("catmull_clark/point_sphere/full1", 0x17487b98b1cdcd65),
    ("loop/torus/plain1", 0x084dba8fd98391f5),
    ("loop/torus/plain2", 0x36717ebd81f51099),
    ("loop/torus/full1", 0x298af3cf00322607),
    ("loop/genus2/plain1", 0x13d10308c9d10b92),
    ("loop/genus2/plain2", 0xf233484a25bb6679),
    ("loop/genus2/full1", 0x37e1c754b7e0dfd7),
    ("loop/open_grid/plain1", 0x22fd158103a1883e),
    ("loop/open_grid/plain2", 0x45745a208d41db7b),
    ("loop/open_grid/full1", 0xf35323a02c7da194),
    ("loop/ico_two_holes/plain1", 0x7e57e9e77fe09d76),
    ("loop/ico_two_holes/plain2", 0x8d7df2f163ed966d),
    ("loop/ico_two_holes/full1", 0xc54735f886f36379),
    ("loop/self_loop/plain1", 0x1bbf800c9b31bad8),
    ("loop/self_loop/plain2", 0x0f6203635f573501),
    ("loop/self_loop/full1", 0xc280c1032dc4bec8),
    ("loop/two_gon/plain1", 0x111fe3af38b5e471),
    ("loop/two_gon/plain2", 0x381c8a7ed886afb5),
    ("loop/two_gon/full1", 0xfb6a5c1f28bce827),
    ("loop/one_two_gon/plain1", 0x069b35066427da11),
    ("loop/one_two_gon/plain2", 0x1c71a61523ec41fb),
    ("loop/one_two_gon/full1", 0xad19027c439aad8e),
    ("loop/handle_loop/plain1", 0x6e83ee109e66ba33),
    ("loop/handle_loop/plain2", 0x22e3155623b6d8cc),
    ("loop/handle_loop/full1", 0x1aadc550e0f81202),
    ("loop/point_sphere/plain1", 0xfd09b6e742597632),
    ("loop/point_sphere/plain2", 0x89a99bd8da900d68),
    ("loop/point_sphere/full1", 0x8d31744025b02caf),
    ("midpoint/torus/plain1", 0xe368d60c68487b82),
    ("midpoint/torus/plain2", 0x005628eb3b47215c),
    ("midpoint/torus/full1", 0xe885a519836ccbbd),
    ("midpoint/genus2/plain1", 0x40af68c38bf1898e),
    ("midpoint/genus2/plain2", 0x5489db9258cff8fe),
    ("midpoint/genus2/full1", 0xcad0c79f7f4a1bdc),
    ("midpoint/open_grid/plain1", 0x02287dca8214debb),
    ("midpoint/open_grid/plain2", 0xb13072703493329e),
    ("midpoint/open_grid/full1", 0x06fdc217070d5263),
    ("midpoint/ico_two_holes/plain1", 0x9f520fd04472d909),
    ("midpoint/ico_two_holes/plain2", 0xb1d27148d51f9bd2),
    ("midpoint/ico_two_holes/full1", 0x2fc90c7afb71793a),
    ("midpoint/self_loop/plain1", 0xd76e1548a8009b8c),
    ("midpoint/self_loop/plain2", 0x9678e3897040e8cc),
    ("midpoint/self_loop/full1", 0x41bb91b6fc73b21a),
    ("midpoint/two_gon/plain1", 0xa509e2cce4f38d0a),
    ("midpoint/two_gon/plain2", 0x80c66443ea4590f7),
    ("midpoint/two_gon/full1", 0x87bebd0d32d1cbd2),
    ("midpoint/one_two_gon/plain1", 0x2079e6af1a068458),
    ("midpoint/one_two_gon/plain2", 0x02fe753480337580),
    ("midpoint/one_two_gon/full1", 0x2a9918b894b41457),
    ("midpoint/handle_loop/plain1", 0x66a36a586c75d0e9),
    ("midpoint/handle_loop/plain2", 0x637407a4251099be),
    ("midpoint/handle_loop/full1", 0x0d2a36b1d0b6c9dc),
    ("midpoint/point_sphere/plain1", 0xd06e4f99423df5a8),
    ("midpoint/point_sphere/plain2", 0x95543a6951b50d4a),
    ("midpoint/point_sphere/full1", 0x9ae985077a83c8ad),
    ("doo_sabin/torus/plain1", 0xdd402e4d3e3b979d),
    ("doo_sabin/torus/plain2", 0x2238f70f202b80b7),
    ("doo_sabin/torus/full1", 0x7d0e965d306e57e2),
    ("doo_sabin/genus2/plain1", 0xba2e0044ddba1db8),
    ("doo_sabin/genus2/plain2", 0x26dd1659e5e337f8),
    ("doo_sabin/genus2/full1", 0x50702be719e526d0),
    ("doo_sabin/open_grid/plain1", 0x48564930a2b72278),
    ("doo_sabin/open_grid/plain2", 0xb417861f501a547a),
    ("doo_sabin/open_grid/full1", 0x5c2fc9c865c2f491),
    ("doo_sabin/ico_two_holes/plain1", 0x6e1751a93463d95b),
    ("doo_sabin/ico_two_holes/plain2", 0xa7795ff73fff95cf),
    ("doo_sabin/ico_two_holes/full1", 0xf5648d3f3b026554),
    ("doo_sabin/self_loop/plain1", 0x8f5858551d77a99e),
    ("doo_sabin/self_loop/plain2", 0xfcbfbbf99bad0978),
    ("doo_sabin/self_loop/full1", 0x905f407d9d3fb67c),
    ("doo_sabin/two_gon/plain1", 0x9f96ac05f9baff9a),
    ("doo_sabin/two_gon/plain2", 0xd9a683cdb7ef9183),
    ("doo_sabin/two_gon/full1", 0xab44e5f108768394),
    ("doo_sabin/one_two_gon/plain1", 0xec404192ef60e651),
    ("doo_sabin/one_two_gon/plain2", 0xd8c9575109e1b5b7),
    ("doo_sabin/one_two_gon/full1", 0xdeb1573251c444c8),
    ("doo_sabin/handle_loop/plain1", 0x5a550953a5dc4bf2),
    ("doo_sabin/handle_loop/plain2", 0x0b4f8b4c1a68a48a),
    ("doo_sabin/handle_loop/full1", 0xfba81295dff1d865),
    ("doo_sabin/point_sphere/plain1", 0x4eb29940e458ac5b),
    ("doo_sabin/point_sphere/plain2", 0xdd67788e62249508),
    ("doo_sabin/point_sphere/full1", 0x2fedcdc612ab26c6),
    ("dual/torus/plain1", 0x0de2ec88432473ff),
    ("dual/torus/plain2", 0x0acdea3121d0edcd),
    ("dual/torus/full1", 0x4a6e77b7798a3a0f),
    ("dual/genus2/plain1", 0xd0615f29aa3b6277),
    ("dual/genus2/plain2", 0x2e8b7b2eef3cbbd2),
    ("dual/genus2/full1", 0xd84e5c2087052924),
    ("dual/open_grid/plain1", 0x943a01554bf48735),
    ("dual/open_grid/plain2", 0x829ad5b88e5da5fd),
    ("dual/open_grid/full1", 0x5914d096a5c17398),
    ("dual/ico_two_holes/plain1", 0x8c802421ce13fcb4),
    ("dual/ico_two_holes/plain2", 0x62e1898298aed5ce),
    ("dual/ico_two_holes/full1", 0xc26696d440ec8aad),
    ("dual/self_loop/plain1", 0xaf1adf6d14a827a5),
    ("dual/self_loop/plain2", 0x2bd4ff023aea8e36),
    ("dual/self_loop/full1", 0x5f48aebe75eb9df9),
    ("dual/two_gon/plain1", 0x3c723ff723362063),
    ("dual/two_gon/plain2", 0x8ffdc497c65f517d),
    ("dual/two_gon/full1", 0x17f3daf84c19cf93),
    ("dual/one_two_gon/plain1", 0xc9abfe5af1a0cfcd),
    ("dual/one_two_gon/plain2", 0x1914269d85e7b155),
    ("dual/one_two_gon/full1", 0x68328f5dd7a159c4),
    ("dual/handle_loop/plain1", 0x3819ac9ff2a4a687),
    ("dual/handle_loop/plain2", 0x19d7e3c75c1c383f),
    ("dual/handle_loop/full1", 0xb0911ccaf16c4bc0),
    ("dual/point_sphere/plain1", 0x1bd1dcd9fc9dda69),
    ("dual/point_sphere/plain2", 0x54edde7e81e07c81),
    ("dual/point_sphere/full1", 0xbe5a2d79e715e6ba),
    ("sqrt3/torus/plain1", 0x045c6064a88dd56c),
    ("sqrt3/torus/plain2", 0xa349406dd819d929),
    ("sqrt3/torus/full1", 0xcb431e7ff6ca497a),
    ("sqrt3/genus2/plain1", 0xa2986d0c2033bf86),
    ("sqrt3/genus2/plain2", 0xd747811f24f23a92),
    ("sqrt3/genus2/full1", 0x9fbf1e919345d042),
    ("sqrt3/open_grid/plain1", 0x7173fe2562d1ac0e),
    ("sqrt3/open_grid/plain2", 0x8b333871a07a7363),
    ("sqrt3/open_grid/full1", 0xeeea7721d058bdf8),
    ("sqrt3/ico_two_holes/plain1", 0x07d54e779753d0ed),
    ("sqrt3/ico_two_holes/plain2", 0x83bbd46495f1b804),
    ("sqrt3/ico_two_holes/full1", 0x50e51a6a62c4ea0e),
    ("sqrt3/self_loop/plain1", 0x173378a3bb4a12b8),
    ("sqrt3/self_loop/plain2", 0x721735f9bfd7d407),
    ("sqrt3/self_loop/full1", 0x2077c1628691fd06),
    ("sqrt3/two_gon/plain1", 0x6721289da732c33d),
    ("sqrt3/two_gon/plain2", 0x027837df615f146f),
    ("sqrt3/two_gon/full1", 0xf9da910ff129219b),
    ("sqrt3/one_two_gon/plain1", 0x3ee041ca5b2f6575),
    ("sqrt3/one_two_gon/plain2", 0x4661930446da0d26),
    ("sqrt3/one_two_gon/full1", 0x295dbe7b21e475a8),
    ("sqrt3/handle_loop/plain1", 0x1c731d10ecd7d2cc),
    ("sqrt3/handle_loop/plain2", 0x36df2acfd79c0c6b),
    ("sqrt3/handle_loop/full1", 0x995b3974f322d68d),
    ("sqrt3/point_sphere/plain1", 0x1020bd1f202ca1db),
    ("sqrt3/point_sphere/plain2", 0x02ada41c87508bed),
    ("sqrt3/point_sphere/full1", 0x6de4e22e051fb4c6),
    ("simplest/torus/plain1", 0x5fac55586ef2d563),
    ("simplest/torus/plain2", 0xe2f981e3d0fc51ae),
    ("simplest/torus/full1", 0x7b3dfe7b78bef313),
    ("simplest/genus2/plain1", 0x7e50fb0cdff4c5c7),
    ("simplest/genus2/plain2", 0x15fd32ddc19982c0),
    ("simplest/genus2/full1", 0x7f8f9e2e51f13f84),
    ("simplest/open_grid/plain1", 0xeb783e9106248074),
    ("simplest/open_grid/plain2", 0x613dd5777f71533a),
    ("simplest/open_grid/full1", 0x323a5fc44b1734a0),
    ("simplest/ico_two_holes/plain1", 0x225a96b6188b40e1),
    ("simplest/ico_two_holes/plain2", 0x7ab92f937227d2d7),
    ("simplest/ico_two_holes/full1", 0x7c7563b0ecb0eccd),
    ("simplest/self_loop/plain1", 0x6dea967b66aede6a),
    ("simplest/self_loop/plain2", 0xc46d7550b200731c),
    ("simplest/self_loop/full1", 0xe69a32b2e4ce92f6),
    ("simplest/two_gon/plain1", 0x854c9b38da4ae5b0),
    ("simplest/two_gon/plain2", 0x308333655b06551b),
    ("simplest/two_gon/full1", 0x1c610777fa973d52),
    ("simplest/one_two_gon/plain1", 0x1943cba150dbf541),
    ("simplest/one_two_gon/plain2", 0x1941789d1d0ba22d),
    ("simplest/one_two_gon/full1", 0x191dd49d7d862712),
    ("simplest/handle_loop/plain1", 0x8764919d56aa1b08),
    ("simplest/handle_loop/plain2", 0xfb68031401fe7658),
    ("simplest/handle_loop/full1", 0x86826bf0cdb2aed7),
    ("simplest/point_sphere/plain1", 0xa44f0171d2b41a86),
    ("simplest/point_sphere/plain2", 0xecd69f25899058f1),
    ("simplest/point_sphere/full1", 0x5e321b103420e281),
    ("honeycomb/torus/plain1", 0xc6779e7556961c7b),
    ("honeycomb/torus/plain2", 0x475cec99630481c0),
    ("honeycomb/torus/full1", 0xa388ca27a513f7cb),
    ("honeycomb/genus2/plain1", 0x070ee4602244aa65),
    ("honeycomb/genus2/plain2", 0xa635adf4ed723376),
    ("honeycomb/genus2/full1", 0xfeb19097243fabd5),
    ("honeycomb/open_grid/plain1", 0x2f2289dc70e3f4da),
    ("honeycomb/open_grid/plain2", 0xa9192c6530b6046d),
    ("honeycomb/open_grid/full1", 0x47f981da3be82f3a),
    ("honeycomb/ico_two_holes/plain1", 0x951405f10722038e),
    ("honeycomb/ico_two_holes/plain2", 0x2e372f28f8b00e3f),
    ("honeycomb/ico_two_holes/full1", 0xa16254da167a1d37),
    ("honeycomb/self_loop/plain1", 0xf541f7586a3c0856),
    ("honeycomb/self_loop/plain2", 0xc8e9737cc94b15ee),
    ("honeycomb/self_loop/full1", 0x7eef3b57ccbdef6a),
    ("honeycomb/two_gon/plain1", 0xbe1454e1987ef922),
    ("honeycomb/two_gon/plain2", 0xff1de8a46c0b6987),
    ("honeycomb/two_gon/full1", 0x2bc397d966b0e08e),
    ("honeycomb/one_two_gon/plain1", 0xd9c666cb78d78d50),
    ("honeycomb/one_two_gon/plain2", 0x591fa590330d697c),
    ("honeycomb/one_two_gon/full1", 0xf73dea6185c2b859),
    ("honeycomb/handle_loop/plain1", 0xed0cd14ef860e14f),
    ("honeycomb/handle_loop/plain2", 0xcd5c363ba0f5a274),
    ("honeycomb/handle_loop/full1", 0x3333dcbce63e61a2),
    ("honeycomb/point_sphere/plain1", 0x5cd290b28d1c9683),
    ("honeycomb/point_sphere/plain2", 0x912d0719214c48d0),
    ("honeycomb/point_sphere/full1", 0x3e3db222d2f0203c),
    ("vertex_truncation/torus/plain1", 0xbca04d5f0f063428),
    ("vertex_truncation/torus/plain2", 0x1bfa9664e77ac7c5),
    ("vertex_truncation/torus/full1", 0x08293f4d8278ced0),
    ("vertex_truncation/genus2/plain1", 0xbc01990d070a384c),
    ("vertex_truncation/genus2/plain2", 0x794c4dd5027ec82d),
    ("vertex_truncation/genus2/full1", 0x993ec5df935f567a),
    ("vertex_truncation/open_grid/plain1", 0x99cac87f4aef6d26),
    ("vertex_truncation/open_grid/plain2", 0xcc3513c185a39d10),
    ("vertex_truncation/open_grid/full1", 0x78535efd027b5912),
    ("vertex_truncation/ico_two_holes/plain1", 0x877e7a9f941eb821),
    ("vertex_truncation/ico_two_holes/plain2", 0x4279c7a8ccc773aa),
    ("vertex_truncation/ico_two_holes/full1", 0xbd6cab4eca2bcc56),
    ("vertex_truncation/self_loop/plain1", 0xb51b23d917dd5179),
    ("vertex_truncation/self_loop/plain2", 0xf434cd533407bbc5),
    ("vertex_truncation/self_loop/full1", 0x1692646221c6daa5),
    ("vertex_truncation/two_gon/plain1", 0xcd906d8736d8c093),
    ("vertex_truncation/two_gon/plain2", 0x4329ca9d59e445a9),
    ("vertex_truncation/two_gon/full1", 0xcd74e9ca967e55f9),
    ("vertex_truncation/one_two_gon/plain1", 0xcdc00b73c9cb01aa),
    ("vertex_truncation/one_two_gon/plain2", 0x4f1460479c7ce8db),
    ("vertex_truncation/one_two_gon/full1", 0x7dc0bfb7d5cb174b),
    ("vertex_truncation/handle_loop/plain1", 0x4eca60f6f00fb2d5),
    ("vertex_truncation/handle_loop/plain2", 0x875e19fb60374168),
    ("vertex_truncation/handle_loop/full1", 0x390e7aa46223e692),
    ("vertex_truncation/point_sphere/plain1", 0xc3ef10d144a11a1d),
    ("vertex_truncation/point_sphere/plain2", 0x11940974385f72b8),
    ("vertex_truncation/point_sphere/full1", 0x5da1fda485873778),
];
