//! TopMod's remeshing menu (TopModLab/TopMod, `topmodx/src/RemeshingMode.cc`
//! and `MainWindowCallbacks.cc`; the schemes in
//! `topmodx/include/dlflaux/DLFLSubdiv.cc`), one file per scheme or tight
//! family. Most of these schemes have no paper: their only description is
//! TopMod's source, which each file names (file and function) and follows;
//! where TopMod's code has an artefact, the file says what differs.
//!
//! Every scheme here is a free function `&Mesh → Result<Mesh>` building its
//! output in one pass from the input's half-edges ([`crate::schemes::keyed::Out`]: faces as
//! corners with edge keys, twins paired by key), so it runs on every closed
//! manifold mesh the other schemes accept: any face size, non-convex faces,
//! self-loops, multi-edges, one-gons, two-gons, any genus. Point-spheres are
//! carried through unchanged; open meshes (hole faces) are refused with a
//! `MeshError` (TopMod has no boundary rules for these schemes). Each
//! scheme's docs state its masks and V', E', F' and face-size histogram
//! from the input's; the tests check them on a corpus.
//!
//! | TopMod menu entry | function |
//! |---|---|
//! | Stellate | [`stellate::stellate`] |
//! | Double Stellate | [`stellate::double_stellate`] |
//! | Stellate with edge removal | [`stellate::stellate_edge_removal`] |
//! | Linear Vertex Insertion | [`linear::linear_vertex_insertion`] |
//! | Subdivide selected faces | [`linear::subdivide_faces`] |
//! | Corner Cutting | [`corner_cutting::corner_cutting`] |
//! | Modified Corner Cutting | [`corner_cutting::modified_corner_cutting`] |
//! | Root-3 | [`compose::root3`] |
//! | Loop-Style Remeshing | [`loop_style::loop_style`] |
//! | Dual Loop-Style (Root-4), Hexagon Preserving | [`loop_style::root4`] |
//! | Dual Hexagon Preserving | [`compose::dual_hexagon_preserving`] |
//! | Dual Loop | [`compose::dual_loop`] |
//! | Pentagonalization | [`pentagonal::pentagonalize`] |
//! | Cubic / Dual Pentagonalization | [`compose::cubic_pentagonalize`], [`compose::dual_pentagonalize`] |
//! | Pentagon Preserving / Dual | [`pentagonal::pentagon_preserving`], [`compose::dual_pentagon_preserving`] |
//! | Dual 12.6.4 / 12.6.4 | [`twelve_six_four::dual_12_6_4`], [`compose::remesh_12_6_4`] |
//! | Checkerboard / Dual | [`checkerboard::checkerboard`], [`compose::dual_checkerboard`] |
//! | Doo-Sabin (BC) | [`compose::doo_sabin_bc`] |
//! | Doo Sabin BC New | [`doo_sabin_bc_new::doo_sabin_bc_new`] |
//! | Double Stellate (Misc.) | [`stellate::double_stellate_misc`] |
//! | Dome | [`extrude::dome`] |
//! | Fractal | [`loop_style::fractal`] |
//! | Extrusions | [`extrude`] |

pub mod checkerboard;
mod checkerboard_dual;
pub mod compose;
pub mod corner_cutting;
mod cubic_pentagonal;
pub mod doo_sabin_bc_new;
mod dual_loop;
pub mod extrude;
mod extrude_platonic;
pub mod linear;
pub mod loop_style;
mod root4_dual;
pub mod pentagonal;
mod root3_dual;
mod pentagonal_dual;
mod pentagonalize_dual;
pub mod stellate;
pub mod twelve_six_four;
mod twelve_six_four_dual;

#[cfg(test)]
pub(crate) mod tests {
    use crate::mesh::Mesh;
    use crate::schemes::hosts::test_meshes::{corpus, handle_cube, n_point_spheres, star_prism};
    use std::collections::BTreeMap;

    /// The scheme corpus plus a non-convex prism and a handle cube.
    pub fn meshes() -> Vec<(&'static str, Mesh)> {
        let mut v = corpus();
        v.push(("star_prism", star_prism()));
        v.push(("handle_cube", handle_cube()));
        v
    }

    /// Face-size histogram without point-sphere faces.
    pub fn hist_of(m: &Mesh) -> BTreeMap<usize, usize> {
        let mut h = BTreeMap::new();
        for f in m.faces() {
            if m.face_halfedge(f).is_some() {
                *h.entry(m.face_degree(f)).or_insert(0) += 1;
            }
        }
        h
    }

    /// Doo-Sabin's histogram: the input's faces, E quads, one k-gon per
    /// valence-k vertex.
    pub fn dual_host_hist(m: &Mesh, (_, e, _): (usize, usize, usize)) -> BTreeMap<usize, usize> {
        let mut h = hist_of(m);
        *h.entry(4).or_insert(0) += e;
        for v in m.vertices() {
            if m.point_sphere_face(v).is_none() {
                *h.entry(m.valence(v)).or_insert(0) += 1;
            }
        }
        h
    }

    /// Runs `scheme` over [`meshes`]: the output validates, keeps the
    /// point-spheres, genus, χ and components, and has the counts
    /// `counts(m, (V, E, F))` (point-spheres left out), then `more`.
    pub fn check_counts(
        name: &str,
        scheme: impl Fn(&Mesh) -> crate::Result<Mesh>,
        counts: impl Fn(&Mesh, (usize, usize, usize)) -> (usize, usize, usize),
        more: impl Fn(&Mesh, &Mesh),
    ) {
        for (mesh, m) in meshes() {
            let ps = n_point_spheres(&m);
            let c = (m.n_vertices() - ps, m.n_edges(), m.n_faces() - ps);
            let r = scheme(&m).unwrap_or_else(|e| panic!("{name} on {mesh}: {e}"));
            r.validate().unwrap_or_else(|e| panic!("{name} on {mesh}: {e}"));
            assert_eq!(n_point_spheres(&r), ps, "{name} on {mesh}: point-spheres");
            let got = (r.n_vertices() - ps, r.n_edges(), r.n_faces() - ps);
            assert_eq!(got, counts(&m, c), "{name} on {mesh}: (V, E, F)");
            assert_eq!(r.genus(), m.genus(), "{name} on {mesh}: genus");
            assert_eq!(r.euler_characteristic(), m.euler_characteristic(), "{name} on {mesh}: χ");
            assert_eq!(r.n_components(), m.n_components(), "{name} on {mesh}: components");
            assert!(r.positions().iter().all(|p| p.is_finite()), "{name} on {mesh}: positions");
            more(&m, &r);
        }
    }

    /// [`check_counts`] and the face-size histogram `hist(m, (V, E, F))`.
    pub fn check(
        name: &str,
        scheme: impl Fn(&Mesh) -> crate::Result<Mesh>,
        counts: impl Fn(&Mesh, (usize, usize, usize)) -> (usize, usize, usize),
        hist: impl Fn(&Mesh, (usize, usize, usize)) -> BTreeMap<usize, usize>,
    ) {
        check_counts(name, scheme, counts, |m, r| {
            let ps = n_point_spheres(m);
            let c = (m.n_vertices() - ps, m.n_edges(), m.n_faces() - ps);
            assert_eq!(hist_of(r), hist(m, c), "{name}: face sizes");
        });
    }

    #[test]
    fn open_meshes_are_refused() {
        let open = crate::schemes::hosts::test_meshes::cube_with_hole();
        let msg = super::stellate::stellate(&open, 0.0).unwrap_err().to_string();
        assert!(msg.contains("boundary loop"), "{msg}");
        assert!(super::loop_style::root4(&open, 0.0, 0.0).is_err());
    }
}
