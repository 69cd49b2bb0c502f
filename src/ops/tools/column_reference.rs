//! The column modelling tool as the keyed builder built it, before its
//! connectivity was written straight into the columns (issue 16): the
//! numbering `columns_direct` reproduces, compared in `column::tests`.

/// The tool as the keyed builder built it: the numbering the direct
/// columns reproduce.
pub(super) fn reference(m: &crate::Mesh, thickness: f64, n: usize) -> crate::Mesh {
    use crate::mesh::HalfedgeId;
    use crate::schemes::keyed::Out;
    let pos = m.wireframe_columns(thickness, n).unwrap().positions().to_vec();
    let (nh, ne) = (m.n_halfedges(), m.n_edges());
    let (n32, m32) = (n as u32, (n / 2) as u32);
    let even = n % 2 == 0;
    let r = |h: HalfedgeId, j: u32| n32 * h.0 + j % n32;
    // keys: column edge (e, j) joins R(2e, j) and R(2e+1, n − j); ring side
    // (h, j) runs R(h, j) → R(h, j+1); rung (h, k) joins R(h, k) and R(rot h, n − k)
    let col = |e: u32, j: u32| n32 * e + j % n32;
    let side = |h: HalfedgeId, j: u32| n32 * ne as u32 + n32 * h.0 + j % n32;
    let rung0 = |h: HalfedgeId, k: u32| n32 * (ne + nh) as u32 + (m32 + 1) * h.0 + k;
    // at a valence-2 vertex the two-corner caps are left out: the second
    // strip uses the first one's top (and, for even n, bottom) rung
    let rung = |h: HalfedgeId, k: u32| {
        let g = m.rotate(h);
        if g != h && m.rotate(g) == h && h.0 > g.0 && (k == 0 || (even && k == m32)) {
            rung0(g, k)
        } else {
            rung0(h, k)
        }
    };
    // spoke of an odd bottom fan: one key per ring point at its rim
    let spoke_base = (n * (ne + nh) + (m32 as usize + 1) * nh) as u32;
    let spoke = |p: u32| spoke_base + p;
    let n_keys = spoke_base as usize + n * nh;
    let mut centre = (n * nh) as u32;
    let mut o = Out::new(pos, n_keys, 2 * n * ne, 8 * n * ne);
    // columns
    for e in m.edges() {
        let (h, tw) = (e.halfedge(), e.halfedge().twin());
        let e = e.0;
        for j in 0..n32 {
            o.c(r(h, j), col(e, j));
            o.c(r(tw, n32 - j), side(tw, n32 - j - 1));
            o.c(r(tw, n32 - j - 1), col(e, j + 1));
            o.c(r(h, j + 1), side(h, j));
            o.end();
        }
    }
    // joints
    for v in m.vertices() {
        
        let h0 = m.vertex_halfedge(v).expect("no point-spheres");
        if m.rotate(h0) == h0 {
            for j in 0..n32 {
                o.c(r(h0, j), side(h0, j));
            }
            o.end();
            continue;
        }
        let mut k = 0;
        let mut h = h0;
        loop {
            let g = m.rotate(h);
            for q in 0..m32 {
                o.c(r(h, q), side(h, q));
                o.c(r(h, q + 1), rung(h, q + 1));
                o.c(r(g, n32 - q - 1), side(g, n32 - q - 1));
                o.c(r(g, n32 - q), rung(h, q));
                o.end();
            }
            k += 1;
            h = g;
            if h == h0 {
                break;
            }
        }
        if k > 2 {
            loop {
                o.c(r(h, 0), rung(h, 0));
                h = m.rotate(h);
                if h == h0 {
                    break;
                }
            }
            o.end();
        }
        if k > 2 || !even {
            // reverse rotation: pred(h) = next(twin h)
            let mut cap = Vec::new();
            loop {
                let p = m.next(h.twin());
                if even {
                    cap.push((r(h, m32), rung(p, m32)));
                } else {
                    cap.push((r(h, m32), side(h, m32)));
                    cap.push((r(h, m32 + 1), rung(p, m32)));
                }
                h = p;
                if h == h0 {
                    break;
                }
            }
            if even || k == 2 {
                for (p, key) in cap {
                    o.c(p, key);
                }
                o.end();
            } else {
                // odd n: a fan of triangles around the cap's centre
                let kk = cap.len();
                for i in 0..kk {
                    let (p, q) = (cap[i].0, cap[(i + 1) % kk].0);
                    o.c(p, cap[i].1);
                    o.c(q, spoke(q));
                    o.c(centre, spoke(p));
                    o.end();
                }
                centre += 1;
            }
        }
    }
    o.finish("wireframe_columns").unwrap()
}
