//! Writing and picturing a D-dimensional body: per-frame OBJ/VTK writers
//! (triangles in the plane, the boundary surface and the tets of a volume)
//! and the per-dimension picture and final state.

use ecc_mesh::{TetMesh, TriMesh, tet_boundary_faces};

use super::context::FinalState;
use crate::body::Body;
use crate::error::SceneError;
use crate::output::OutputDir;
use crate::pictures::{self, Picture};
use crate::spec::FrameFormat;

/// Writes frames of a D-dimensional body.
pub(crate) trait FrameWriter<const D: usize> {
    fn write(
        &self,
        out: &mut OutputDir,
        name: &str,
        x: &[[f64; D]],
        formats: &[FrameFormat],
    ) -> Result<(), SceneError>;
}

struct TriWriter {
    mesh: TriMesh,
    rest: Vec<[f64; 2]>,
}

impl FrameWriter<2> for TriWriter {
    fn write(
        &self,
        out: &mut OutputDir,
        name: &str,
        x: &[[f64; 2]],
        formats: &[FrameFormat],
    ) -> Result<(), SceneError> {
        let mut m = self.mesh.clone();
        m.positions = x.iter().map(|p| [p[0], p[1], 0.0]).collect();
        for f in formats {
            match f {
                FrameFormat::Obj => out.obj(&format!("{name}.obj"), &m)?,
                FrameFormat::Vtk => {
                    let disp: Vec<f64> = x
                        .iter()
                        .zip(&self.rest)
                        .flat_map(|(p, r)| [p[0] - r[0], p[1] - r[1], 0.0])
                        .collect();
                    out.vtk_tri(&format!("{name}.vtk"), &m, &[("displacement", &disp, 3)])?
                }
            }
        }
        Ok(())
    }
}

struct TetWriter {
    tets: Vec<[usize; 4]>,
    rest: Vec<[f64; 3]>,
    /// Boundary faces in compact numbering and the vertex each compact id came from.
    faces: Vec<[usize; 3]>,
    surface_vertices: Vec<usize>,
}

impl TetWriter {
    fn new(tets: &[[usize; 4]], rest: &[[f64; 3]]) -> Self {
        let faces = tet_boundary_faces(tets);
        let mut index = vec![usize::MAX; rest.len()];
        let mut surface_vertices = Vec::new();
        let faces = faces
            .into_iter()
            .map(|f| {
                f.map(|v| {
                    if index[v] == usize::MAX {
                        index[v] = surface_vertices.len();
                        surface_vertices.push(v);
                    }
                    index[v]
                })
            })
            .collect();
        TetWriter {
            tets: tets.to_vec(),
            rest: rest.to_vec(),
            faces,
            surface_vertices,
        }
    }
}

impl FrameWriter<3> for TetWriter {
    fn write(
        &self,
        out: &mut OutputDir,
        name: &str,
        x: &[[f64; 3]],
        formats: &[FrameFormat],
    ) -> Result<(), SceneError> {
        for f in formats {
            match f {
                FrameFormat::Obj => {
                    let m = TriMesh {
                        positions: self.surface_vertices.iter().map(|&v| x[v]).collect(),
                        triangles: self.faces.clone(),
                        uvs: None,
                    };
                    out.obj(&format!("{name}.obj"), &m)?
                }
                FrameFormat::Vtk => {
                    let m = TetMesh {
                        positions: x.to_vec(),
                        tets: self.tets.clone(),
                    };
                    let disp: Vec<f64> = x
                        .iter()
                        .zip(&self.rest)
                        .flat_map(|(p, r)| [p[0] - r[0], p[1] - r[1], p[2] - r[2]])
                        .collect();
                    out.vtk_tet(&format!("{name}.vtk"), &m, &[("displacement", &disp, 3)])?
                }
            }
        }
        Ok(())
    }
}

/// A body kind that can be written and pictured.
pub(crate) trait Dim<const D: usize> {
    fn writer(body: &Body<D>) -> Box<dyn FrameWriter<D>>;
    fn picture(
        body: &Body<D>,
        shots: &[(usize, Vec<[f64; D]>)],
        view: &pictures::View<'_>,
    ) -> Picture;
    /// The picture with the scene's fibres (one rest direction per element) drawn.
    fn picture_fibres(
        body: &Body<D>,
        shots: &[(usize, Vec<[f64; D]>)],
        view: &pictures::View<'_>,
        dirs: &[[f64; D]],
    ) -> Picture;
    fn state(body: &Body<D>, x: Vec<[f64; D]>) -> FinalState;
}

pub(crate) struct Dims;

impl Dim<2> for Dims {
    fn writer(body: &Body<2>) -> Box<dyn FrameWriter<2>> {
        let (tris, _) = body.elements.as_chunks::<3>();
        Box::new(TriWriter {
            mesh: TriMesh {
                positions: body.rest.iter().map(|p| [p[0], p[1], 0.0]).collect(),
                triangles: tris.to_vec(),
                uvs: None,
            },
            rest: body.rest.clone(),
        })
    }

    fn picture(
        body: &Body<2>,
        shots: &[(usize, Vec<[f64; 2]>)],
        view: &pictures::View<'_>,
    ) -> Picture {
        let (tris, _) = body.elements.as_chunks::<3>();
        pictures::planar(tris, &body.rest, shots, view)
    }

    fn picture_fibres(
        body: &Body<2>,
        shots: &[(usize, Vec<[f64; 2]>)],
        view: &pictures::View<'_>,
        dirs: &[[f64; 2]],
    ) -> Picture {
        let (tris, _) = body.elements.as_chunks::<3>();
        let fibres = pictures::Fibres {
            rest: &body.rest,
            dirs,
        };
        pictures::planar_fibres(tris, shots, view, &fibres)
    }

    fn state(body: &Body<2>, x: Vec<[f64; 2]>) -> FinalState {
        let (tris, _) = body.elements.as_chunks::<3>();
        FinalState::Planar {
            rest: body.rest.clone(),
            x,
            triangles: tris.to_vec(),
        }
    }
}

impl Dim<3> for Dims {
    fn writer(body: &Body<3>) -> Box<dyn FrameWriter<3>> {
        let (tets, _) = body.elements.as_chunks::<4>();
        Box::new(TetWriter::new(tets, &body.rest))
    }

    fn picture(
        body: &Body<3>,
        shots: &[(usize, Vec<[f64; 3]>)],
        view: &pictures::View<'_>,
    ) -> Picture {
        let (tets, _) = body.elements.as_chunks::<4>();
        pictures::volume(tets, shots, view)
    }

    fn picture_fibres(
        body: &Body<3>,
        shots: &[(usize, Vec<[f64; 3]>)],
        view: &pictures::View<'_>,
        dirs: &[[f64; 3]],
    ) -> Picture {
        let (tets, _) = body.elements.as_chunks::<4>();
        let fibres = pictures::Fibres {
            rest: &body.rest,
            dirs,
        };
        pictures::volume_fibres(tets, shots, view, &fibres)
    }

    fn state(body: &Body<3>, x: Vec<[f64; 3]>) -> FinalState {
        let (tets, _) = body.elements.as_chunks::<4>();
        FinalState::Volume {
            rest: body.rest.clone(),
            x,
            tets: tets.to_vec(),
        }
    }
}
