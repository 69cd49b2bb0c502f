//! Generalized Sierpinski polyhedra: the remeshing scheme of the Sierpinski
//! paper, section 4 (Srinivasan & Akleman, "Connected & Manifold Sierpinsky
//! Polyhedra"), also the high-genus dissertation, ch. VI.5.
//!
//! One iteration, on any closed orientable 2-manifold mesh:
//!
//! 1. every edge that is not a self-loop is subdivided at its midpoint;
//! 2. at every corner of every old vertex the edge cutting the corner
//!    triangle off is inserted (between the midpoints on either side);
//! 3. at every midpoint a self-loop is inserted between its two corners on
//!    the central faces left by step 2.
//!
//! The central faces disappear in step 3 and every old vertex becomes the
//! apex of a pyramid whose base ("back face") runs through the midpoints
//! around it, one self-loop at each. The pyramids touch only at midpoints and
//! the self-loops join them: one connected manifold whose genus grows by a
//! factor four per iteration.
//!
//! # Corners next to self-loops
//!
//! Self-loops are never subdivided, so an old vertex may have self-loops
//! between the two non-loop sides of one of its corners (on the second
//! iteration every corner of a midpoint of the first has one). The paper's
//! corner `{a, v, b}` is read here as the *generalized corner*: the stretch of
//! a face from one non-loop side to the next, self-loops at `v` in between
//! included. The cut of step 2 joins the midpoints of those two non-loop
//! sides, so the self-loops stay with the corner triangle: exactly what keeps
//! two sub-pyramids at a former midpoint joined through their self-loop. A
//! face whose sides are all self-loops (one vertex only) has no midpoint and is
//! kept as it is, as are point-spheres.
//!
//! For a non-loop half-edge `h` let `ν(h)` be the next non-loop half-edge of
//! its face. Step 3 closes, around each old vertex `v`, the cycles of
//! `σ(h) = ν(twin(h))` on the non-loop half-edges leaving `v`: the *cones* of
//! `v`. A vertex without self-loops has one cone (σ is then the rotation); a
//! midpoint of an earlier iteration has two, one per pyramid it joins. Each
//! cone gives one back face.
//!
//! # Open meshes: refused
//!
//! The rule has no boundary version, and its natural extension does not
//! give a surface with boundary. Read on the capped mesh, a hole's corner
//! triangles would become the new holes: the two at the ends of a boundary
//! edge share that edge's midpoint, so every boundary midpoint would lie on
//! two boundary loops (a pinch, not a manifold with boundary); filling the
//! hole instead would close it silently. [`sierpinski`] therefore refuses
//! open meshes with a [`MeshError::Precondition`] that says so.
//!
//! # Count formulas
//!
//! With `L` self-loops, `N = E − L` non-loop edges, `K` cones, `D` cones with
//! a single half-edge (a vertex met by one non-loop edge end only), `F₀` faces
//! with no non-loop side (point-spheres included) and `C` components, one
//! iteration gives
//!
//! ```text
//! V' = V + N            E' = E + 4N          F' = 2N + K + F₀
//! L' = L + N + D        K' = K + 2N          D' = 2D        F₀' = F₀ + D     C' = C
//! N' = 4N − D           χ' = V − E − N + K + F₀         genus' = C − χ'/2
//! ```
//!
//! (`2N` corner triangles, one per non-loop half-edge; `K` back faces; the
//! `2N` cuts are self-loops only at the `D` single-half-edge cones, whose
//! back faces are then two-gons of self-loops.) The
//! usual case is `D = 0` (every vertex meets at least two non-loop edge ends);
//! then after `n ≥ 1` iterations, with `s = (4ⁿ − 1)/3`,
//!
//! ```text
//! Vₙ = V + N·s     Eₙ = E + 4N·s     Fₙ = K + F₀ + 2N·s     Lₙ = L + N·s
//! χₙ = V − E + K + F₀ − N·s          genusₙ = C − χₙ/2
//! ```
//!
//! For a mesh without self-loops or point-spheres `K = V`, `F₀ = 0`, so
//! `χₙ = 2V − E − E·s`; the tetrahedron gives genus `4ⁿ − 1`: 3, 15, 63.
//! [`SierpinskiCounts`] evaluates the recurrence (any `D`) for the tests.
//!
//! # Implementation
//!
//! [`sierpinski`] builds the output in one pass with
//! [`Mesh::from_corner_twins`], O(output): corner triangles, then back faces,
//! then the kept all-loop faces, every twin found by index arithmetic.
//! [`sierpinski_by_operators`] is the paper's algorithm written with the
//! fundamental operators (SubdivideEdge as CreateVertex + 2 InsertEdge +
//! DeleteEdge); it is the readable statement and the tests prove both agree.

use crate::error::{MeshError, Result};
use crate::mesh::{Corner, FaceStart, HalfedgeId, Mesh, MAX_ELEMENTS};
use glam::DVec3;

const NONE: u32 = u32::MAX;

/// Per-half-edge data of the input shared by the builder and the counts.
struct Walk {
    /// For a non-loop half-edge: the next non-loop half-edge of its face (ν).
    nu: Vec<u32>,
    /// For a non-loop half-edge: self-loops between it and ν(h) in its face.
    loops_after: Vec<u32>,
}

impl Walk {
    fn of(m: &Mesh) -> Result<Walk> {
        let (next, vert, _) = m.halfedge_columns();
        let nh = next.len();
        let is_loop = |h: usize| vert[h] == vert[h ^ 1];
        // (ν(h), loops after h); written chunk by chunk, stopping once
        // cancelled (`cancel::par_collect`: a collect, then an unzip, wrote
        // 2 × 8 bytes per half-edge of fresh memory with no poll, up to a
        // second of Ctrl-C latency on a 2M-face torus)
        let walk = |h: usize| -> (u32, u32) {
            if is_loop(h) {
                return (NONE, 0);
            }
            let mut k = 0u32;
            let mut x = next[h] as usize;
            while is_loop(x) {
                k += 1;
                x = next[x] as usize;
            }
            (x as u32, k)
        };
        let nu = crate::cancel::par_collect(nh, |h| walk(h).0)?;
        let loops_after = crate::cancel::par_collect(nh, |h| walk(h).1)?;
        Ok(Walk { nu, loops_after })
    }

    #[inline]
    fn is_nonloop(&self, h: usize) -> bool {
        self.nu[h] != NONE
    }

    /// σ(h) = ν(twin(h)): the next non-loop half-edge leaving the tail of `h`
    /// in its cone.
    #[inline]
    fn sigma(&self, h: usize) -> usize {
        self.nu[h ^ 1] as usize
    }
}

/// Why open meshes are refused (module docs, "Open meshes").
const OPEN_MESHES: &str = "Sierpinski's rule (Srinivasan & Akleman, section 4) has no boundary version: on an open mesh \
the pyramids of two neighbouring boundary vertices would meet at the boundary edge's midpoint, which would lie on two \
boundary loops (a pinch, not a manifold with boundary), and treating the holes as faces would fill them; close the \
holes with faces first";

/// One Sierpinski iteration (see the module docs), built in one pass.
///
/// Vertex `i < V` of the output is vertex `i` of the input; the midpoint of
/// the `k`-th non-loop edge (in edge order) is vertex `V + k`. Works on every
/// closed manifold mesh, its own output included; a mesh made of self-loops
/// and point-spheres only is returned unchanged. An open mesh is refused
/// (`Precondition`, module docs).
pub fn sierpinski(m: &Mesh) -> Result<Mesh> {
    build(m, false).map(|r| r.0)
}

/// One iteration with what `req` asks for; without requests it is
/// [`sierpinski`]. Positions are linear (old vertices and midpoints), so
/// the stencils are exact. Origins (the lowest-dimensional input element an
/// output element lies in): old vertex → (VERTEX, v), midpoint of e →
/// (EDGE, e); the corner triangle of non-loop half-edge h lies inside
/// face(h) → (FACE, face(h)); the back face of a cone of v runs around v →
/// (VERTEX, v); a kept all-loop face → (FACE, f). Edges: the halves of a
/// subdivided edge, the kept self-loops and the self-loop inserted at the
/// midpoint of e → (EDGE, e); a corner cut lies inside its face → (FACE, f).
/// Open meshes are refused, as by [`sierpinski`]. No sharpness is carried.
/// This scheme has no sharpness rules: `req.creases` is ignored and
/// `Level.creases` is `None` (creases are dropped).
pub fn sierpinski_level(m: &Mesh, req: &super::level::Request) -> Result<super::level::Level> {
    use super::level::{Level, Origins, EDGE, FACE, VERTEX};
    let (mesh, co) = build(m, req.origins)?;
    if !req.stencils && !req.origins {
        return Ok(Level::plain(mesh));
    }
    let (nv, ne) = (m.n_vertices(), m.n_edges());
    let (_, vert, face) = m.halfedge_columns();
    let w = Walk::of(m)?;
    let mids: Vec<u32> = (0..ne as u32).filter(|&e| w.is_nonloop(2 * e as usize)).collect();
    let stencils = if req.stencils {
        Some(super::stencil::Stencils::build(nv + mids.len(), nv, |i, row| {
            if i < nv {
                row.add(i as u32, 1.0);
            } else {
                let e = mids[i - nv] as usize;
                row.add(vert[2 * e], 0.5);
                row.add(vert[2 * e + 1], 0.5);
            }
        })?)
    } else {
        None
    };
    let origins = if req.origins {
        let mut o = Origins::with_capacity(mesh.n_vertices(), mesh.n_edges(), mesh.n_faces());
        o.vertex_kind.extend(std::iter::repeat(VERTEX).take(nv).chain(std::iter::repeat(EDGE).take(mids.len())));
        o.vertex.extend((0..nv as u32).chain(mids.iter().copied()));
        // faces: pieces (non-loop half-edges in order), back faces (cones in order of first half-edge), kept faces
        let nh = m.n_halfedges();
        let mut seen = vec![false; nh];
        let mut cones = Vec::new();
        for h in 0..nh {
            if w.is_nonloop(h) {
                o.face_kind.push(FACE);
                o.face.push(face[h]);
                if !seen[h] {
                    let mut b = h;
                    loop {
                        seen[b] = true;
                        b = w.sigma(b);
                        if b == h {
                            break;
                        }
                    }
                    cones.push(vert[h]);
                }
            }
        }
        o.face_kind.extend(std::iter::repeat(VERTEX).take(cones.len()));
        o.face.extend(cones);
        for f in 0..m.n_faces() {
            let s = m.f_start[f];
            let all_loops = s & crate::mesh::POINT != 0 || m.face_halfedges(crate::FaceId(f as u32)).all(|h| !w.is_nonloop(h.idx()));
            if all_loops {
                o.face_kind.push(FACE);
                o.face.push(f as u32);
            }
        }
        super::corner_origins::edge_origins_by_corner(&mesh, &mut o, |c| co[c])?;
        Some(o)
    } else {
        None
    };
    Ok(Level { mesh, stencils, origins, creases: None })
}

/// [`sierpinski`], and with `want_origins` the origin of every output
/// corner's side (see [`sierpinski_level`]).
fn build(m: &Mesh, want_origins: bool) -> Result<(Mesh, Vec<(u8, u32)>)> {
    use super::level::{EDGE, FACE};
    m.refuse_open("sierpinski", OPEN_MESHES)?;
    let nv = m.n_vertices();
    let nh = m.n_halfedges();
    let (_, vert, _) = m.halfedge_columns();
    let w = Walk::of(m)?;

    // --- counts and the numbering of midpoints (non-loop edges in order);
    // large buffers below are written by polled loops or `cancel::par_*`,
    // never by `vec![x; n]`'s unpolled fill of fresh memory (Ctrl-C latency)
    let mut mid = Vec::with_capacity(nh / 2);
    let mut mid_edge = Vec::new();
    let mut n_mid = 0usize;
    for e in 0..nh / 2 {
        crate::cancel::poll(e)?;
        if w.is_nonloop(2 * e) {
            mid.push((nv + n_mid) as u32);
            mid_edge.push(e as u32);
            n_mid += 1;
        } else {
            mid.push(NONE);
        }
    }
    let n_out_vertices = nv + n_mid;
    // 2N pieces of (loops + 3) corners, back faces 2 corners per non-loop
    // half-edge, kept faces as they are
    let n_loops = nh / 2 - n_mid;
    let piece_corners = 3 * 2 * n_mid + 2 * n_loops; // loops in pieces ≤ all loop half-edges
    if n_out_vertices > MAX_ELEMENTS || piece_corners + 4 * n_mid > MAX_ELEMENTS {
        return Err(MeshError::InvalidArgument(format!(
            "sierpinski: the output ({n_out_vertices} vertices, about {} corners) exceeds the 31-bit id range",
            piece_corners + 4 * n_mid
        )));
    }

    // --- positions: old vertices, then midpoints (made once the corner
    // lists are freed, issue 19, unless a point-sphere needs the general build)
    let old = m.positions();
    let points = move || -> Result<Vec<DVec3>> {
        crate::cancel::par_collect(n_out_vertices, |i| {
            if i < nv {
                old[i]
            } else {
                let e = mid_edge[i - nv] as usize;
                0.5 * (old[vert[2 * e] as usize] + old[vert[2 * e + 1] as usize])
            }
        })
    };

    // --- layout: piece of h at base[h], back-face slots, kept faces last
    let mut base = crate::cancel::par_filled(nh, NONE)?;
    let mut sizes: Vec<u32> = Vec::with_capacity(2 * n_mid + 2 * n_mid / 3 + 16);
    let mut n_corners = 0u32;
    for h in 0..nh {
        crate::cancel::poll(h)?;
        if w.is_nonloop(h) {
            base[h] = n_corners;
            let s = w.loops_after[h] + 3;
            sizes.push(s);
            n_corners += s;
        }
    }
    // cones: position of each non-loop half-edge in its back face
    let back0 = n_corners;
    let mut cone_pos = crate::cancel::par_filled(nh, NONE)?;
    let mut next_pos = 0u32;
    for h in 0..nh {
        crate::cancel::poll(h)?;
        if !w.is_nonloop(h) || cone_pos[h] != NONE {
            continue;
        }
        let mut b = h;
        let mut len = 0u32;
        loop {
            cone_pos[b] = next_pos;
            next_pos += 1;
            len += 1;
            b = w.sigma(b);
            if b == h {
                break;
            }
        }
        sizes.push(2 * len);
    }
    n_corners += 2 * next_pos;
    // faces without a non-loop side
    let kept: Vec<_> = m
        .faces()
        .filter(|&f| match m.face_start(f) {
            FaceStart::Point(_) => true,
            FaceStart::Halfedge(_) => m.face_halfedges(f).all(|h| !w.is_nonloop(h.idx())),
        })
        .collect();
    let kept0 = n_corners;
    for &f in &kept {
        let s = m.face_degree(f) as u32;
        sizes.push(s);
        n_corners += s;
    }
    let nc = n_corners as usize;

    // --- output slot of every input self-loop half-edge
    let mut loop_slot = crate::cancel::par_filled(nh, NONE)?;
    for h in 0..nh {
        crate::cancel::poll(h)?;
        if w.is_nonloop(h) {
            let mut x = m.next(HalfedgeId(h as u32)).idx();
            for j in 0..w.loops_after[h] {
                loop_slot[x] = base[h] + 1 + j;
                x = m.next(HalfedgeId(x as u32)).idx();
            }
        }
    }
    {
        let mut c = kept0;
        for &f in &kept {
            for h in m.face_halfedges(f) {
                loop_slot[h.idx()] = c;
                c += 1;
            }
            if m.face_halfedge(f).is_none() {
                c += 1;
            }
        }
    }

    // --- corners and twins
    let mut cv = vec![0u32; nc];
    let mut tw = crate::cancel::par_filled(nc, NONE)?;
    let mut co = if want_origins { crate::cancel::par_filled(nc, (EDGE, 0u32))? } else { Vec::new() };
    // π(h), the inverse of ν: h's first half is corner k + 1 of the
    // triangle of π(h), the non-loop half-edge before h in its face
    let mut pi = crate::cancel::par_filled(nh, NONE)?;
    for h in 0..nh {
        crate::cancel::poll(h)?;
        if w.is_nonloop(h) {
            pi[w.nu[h] as usize] = h as u32;
        }
    }
    let fh_slot = |h: usize| -> u32 {
        let p = pi[h] as usize;
        base[p] + w.loops_after[p] + 1
    };
    for h in 0..nh {
        crate::cancel::poll(h)?;
        if !w.is_nonloop(h) {
            continue;
        }
        let b = base[h] as usize;
        let k = w.loops_after[h] as usize;
        let v = vert[h ^ 1]; // head of h: the apex of this corner triangle
        let nu = w.nu[h] as usize;
        let mh = mid[h >> 1];
        // second half of h: mid(h) -> v
        cv[b] = mh;
        tw[b] = fh_slot(h ^ 1);
        // self-loops at v
        let mut x = m.next(HalfedgeId(h as u32)).idx();
        for j in 0..k {
            cv[b + 1 + j] = v;
            tw[b + 1 + j] = loop_slot[x ^ 1];
            x = m.next(HalfedgeId(x as u32)).idx();
        }
        // first half of ν(h): v -> mid(ν(h))
        cv[b + k + 1] = v;
        tw[b + k + 1] = base[nu ^ 1];
        // cut, triangle side: mid(ν(h)) -> mid(h); twin in the back face of cone element twin(h)
        cv[b + k + 2] = mid[nu >> 1];
        tw[b + k + 2] = back0 + 2 * cone_pos[h ^ 1] + 1;
        if want_origins {
            co[b] = (EDGE, (h >> 1) as u32);
            let mut x = m.next(HalfedgeId(h as u32)).idx();
            for j in 0..k {
                co[b + 1 + j] = (EDGE, (x >> 1) as u32);
                x = m.next(HalfedgeId(x as u32)).idx();
            }
            co[b + k + 1] = (EDGE, (nu >> 1) as u32);
            co[b + k + 2] = (FACE, m.he_face[h]);
        }
    }
    for bb in 0..nh {
        crate::cancel::poll(bb)?;
        if !w.is_nonloop(bb) {
            continue;
        }
        let s = (back0 + 2 * cone_pos[bb]) as usize;
        let mb = mid[bb >> 1];
        // self-loop at mid(b); its twin lies in the back face of the other end's cone
        cv[s] = mb;
        tw[s] = back0 + 2 * cone_pos[bb ^ 1];
        // cut, back side: mid(b) -> mid(σ(b)); twin in the triangle of twin(b)
        cv[s + 1] = mb;
        let t = bb ^ 1;
        tw[s + 1] = base[t] + w.loops_after[t] + 2;
        if want_origins {
            co[s] = (EDGE, (bb >> 1) as u32);
            co[s + 1] = (FACE, m.he_face[t]);
        }
    }
    {
        let mut c = kept0 as usize;
        for &f in &kept {
            match m.face_start(f) {
                FaceStart::Point(v) => {
                    cv[c] = v.0;
                    tw[c] = NONE;
                    c += 1;
                }
                FaceStart::Halfedge(_) => {
                    for h in m.face_halfedges(f) {
                        cv[c] = vert[h.idx()];
                        tw[c] = loop_slot[h.idx() ^ 1];
                        if want_origins {
                            co[c] = (EDGE, (h.idx() >> 1) as u32);
                        }
                        c += 1;
                    }
                }
            }
        }
    }
    drop((base, cone_pos, loop_slot, pi, mid));
    if tw.contains(&NONE) {
        // a kept point-sphere: its corner has no twin
        return Ok((Mesh::from_corner_twins(points()?, &sizes, &cv, &tw)?, co));
    }
    // the twins are closed forms above, numbered here as `from_corner_twins`
    // numbers them (which test builds also run, and compare)
    #[cfg(test)]
    let reference = Mesh::from_corner_twins(points()?, &sizes, &cv, &tw);
    let holes = vec![false; sizes.len()];
    let (mesh, ()) = Mesh::from_trusted_twins(n_out_vertices, sizes, cv, tw, holes, || Ok((points()?, ())))?;
    #[cfg(test)]
    assert!(reference.as_ref() == Ok(&mesh), "sierpinski: the trusted-twin build differs from from_corner_twins");
    Ok((mesh, co))
}

/// `iterations` Sierpinski steps.
pub fn sierpinski_iterated(m: &Mesh, iterations: usize) -> Result<Mesh> {
    let mut cur = m.clone();
    for _ in 0..iterations {
        cur = sierpinski(&cur)?;
    }
    Ok(cur)
}

/// The paper's algorithm (section 4) with the fundamental operators, on a
/// copy of `m`: SubdivideEdge (as CreateVertex, two InsertEdge and a
/// DeleteEdge), then InsertEdge for the corner cuts and for the self-loops.
/// Quadratic in the worst case (DeleteEdge walks faces); meant for tests and
/// as the readable statement of [`sierpinski`], which gives the same mesh up
/// to the numbering of edges and faces (vertices are numbered alike).
pub fn sierpinski_by_operators(m: &Mesh) -> Result<Mesh> {
    let w = Walk::of(m)?;
    let nh = m.n_halfedges();
    let mut out = m.clone();

    // 1. SubdivideEdge on every non-loop edge, in edge order. With e1 the
    //    edge a → p and e2 the edge p → b, DeleteEdge(e) moves e2 (the last
    //    edge) into id e, so afterwards 2e is p → b and 2e+1 is b → p.
    let mut first_half = vec![NONE; nh];
    let mut second_half = vec![NONE; nh];
    for e in 0..nh / 2 {
        let h = HalfedgeId(2 * e as u32);
        if !w.is_nonloop(h.idx()) {
            continue;
        }
        let (a, b) = (out.vertex(h), out.head(h));
        let p = 0.5 * (out.position(a) + out.position(b));
        let (pv, _) = out.create_vertex(p)?;
        let e1 = out.insert_edge(Corner::Halfedge(h), Corner::Point(pv))?;
        let at_p = e1.halfedge().twin(); // p -> a, the corner at p in the face of h
        let e2 = out.insert_edge(Corner::Halfedge(at_p), Corner::Halfedge(out.next(h)))?;
        debug_assert_eq!(e2.idx(), out.n_edges() - 1);
        out.delete_edge(h.edge())?;
        first_half[2 * e] = e1.halfedge().0;
        second_half[2 * e] = 2 * e as u32;
        first_half[2 * e + 1] = 2 * e as u32 + 1;
        second_half[2 * e + 1] = e1.halfedge().0 + 1;
    }

    // 2. cut every generalized corner: from the corner at mid(h) (second
    //    half of h) to the corner at mid(ν(h)) in the face being cut, i.e.
    //    the corner after the first half of ν(h). The new half-edge 2e runs
    //    mid(h) -> mid(ν(h)) on the central side.
    let mut central = vec![NONE; nh];
    for h in 0..nh {
        crate::cancel::poll(h)?;
        if !w.is_nonloop(h) {
            continue;
        }
        let c1 = HalfedgeId(second_half[h]);
        let c2 = out.next(HalfedgeId(first_half[w.nu[h] as usize]));
        let e = out.insert_edge(Corner::Halfedge(c1), Corner::Halfedge(c2))?;
        central[h] = e.halfedge().0;
    }

    // 3. a self-loop at every midpoint between its two corners on central faces
    for e in 0..nh / 2 {
        if w.is_nonloop(2 * e) {
            out.insert_edge(Corner::Halfedge(HalfedgeId(central[2 * e])), Corner::Halfedge(HalfedgeId(central[2 * e + 1])))?;
        }
    }
    Ok(out)
}

/// The quantities that drive the Sierpinski count formulas (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SierpinskiCounts {
    pub vertices: u64,
    pub edges: u64,
    pub faces: u64,
    pub self_loops: u64,
    /// `K`: cycles of σ(h) = ν(twin(h)) on the non-loop half-edges.
    pub cones: u64,
    /// `D`: cones with one half-edge.
    pub lone_cones: u64,
    /// `F₀`: faces without a non-loop side (point-spheres included).
    pub loop_faces: u64,
    pub components: u64,
}

impl SierpinskiCounts {
    /// Measures `m` (cancellable, [`crate::cancel`]).
    pub fn of(m: &Mesh) -> Result<Self> {
        let w = Walk::of(m)?;
        let nh = m.n_halfedges();
        let mut seen = vec![false; nh];
        let (mut cones, mut lone) = (0u64, 0u64);
        for h in 0..nh {
            if !w.is_nonloop(h) || seen[h] {
                continue;
            }
            cones += 1;
            let mut b = h;
            let mut len = 0;
            loop {
                seen[b] = true;
                len += 1;
                b = w.sigma(b);
                if b == h {
                    break;
                }
            }
            if len == 1 {
                lone += 1;
            }
        }
        let loop_faces = m
            .faces()
            .filter(|&f| m.face_halfedges(f).all(|h| !w.is_nonloop(h.idx())))
            .count() as u64;
        Ok(SierpinskiCounts {
            vertices: m.n_vertices() as u64,
            edges: m.n_edges() as u64,
            faces: m.n_faces() as u64,
            self_loops: m.n_self_loops() as u64,
            cones,
            lone_cones: lone,
            loop_faces,
            components: m.n_components() as u64,
        })
    }

    /// The counts after one more iteration (the recurrence of the module docs).
    pub fn next(&self) -> Self {
        let n = self.edges - self.self_loops;
        SierpinskiCounts {
            vertices: self.vertices + n,
            edges: self.edges + 4 * n,
            faces: 2 * n + self.cones + self.loop_faces,
            self_loops: self.self_loops + n + self.lone_cones,
            cones: self.cones + 2 * n,
            lone_cones: 2 * self.lone_cones,
            loop_faces: self.loop_faces + self.lone_cones,
            components: self.components,
        }
    }

    /// The counts after `iterations` more iterations.
    pub fn after(&self, iterations: usize) -> Self {
        (0..iterations).fold(*self, |c, _| c.next())
    }

    pub fn euler_characteristic(&self) -> i64 {
        self.vertices as i64 - self.edges as i64 + self.faces as i64
    }

    pub fn genus(&self) -> i64 {
        self.components as i64 - self.euler_characteristic() / 2
    }
}

#[cfg(test)]
#[path = "sierpinski_tests.rs"]
mod tests;
