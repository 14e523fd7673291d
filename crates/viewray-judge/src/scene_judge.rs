//! The scene's camera judge that `viewray compare` and `viewray grade` hand to
//! viewray-compare ([`viewray_compare::CameraJudge`]): prepared once per scene, it judges
//! a picture's edges against the right camera and the catalogue's mistaken ones, looks
//! for a moved eye when none explains them, and answers in the catalogue's words.

use viewray_camera::{Mistake, Projection};
use viewray_compare::{
    CANDIDATE_MARGIN, CameraFinding, CameraJudge, CameraMistake, CatalogueEntry, GeometryVerdict,
    PictureEdges, RgbaImage,
};
use viewray_scene::Scene;

use crate::eye::{self, EyeSearch, Seen};
use crate::picture::{CameraVerdict, PictureJudge};

/// How far from every boundary (beyond the pixels on and next to it) a pixel must be to
/// count as inside a surface, where appearance is measured: the width of the image
/// judgement's blur, 2 px, so that the blurred pictures' interiors hold no edge.
const INTERIOR_MARGIN: usize = 2;

/// A scene prepared for judging pictures' cameras: the right camera's label map and the
/// catalogue's, the pixels inside surfaces, and what a moved eye's search needs.
#[derive(Debug)]
pub struct SceneJudge {
    scene: Scene,
    pictures: PictureJudge,
    interior: Vec<bool>,
    eye: EyeSearch,
    /// Whether the right camera explains the reference's own edges: if it does not, no
    /// picture of this scene can convict a camera, and every finding but a right camera is
    /// [`CameraFinding::Unjudged`].
    judges: bool,
    /// Whether the camera has a lens of some aperture: its pictures are blurred out of
    /// focus as much as their sample count lets them (one sample is a pinhole's picture),
    /// so a picture blurred unlike the reference is explained by no sharp map.
    defocus: bool,
}

impl SceneJudge {
    /// Prepares `scene` (loaded at the size of `reference`, the course's render of it):
    /// labels it through its camera and every catalogue entry that fits it
    /// ([`PictureJudge::new`]), and judges `reference` itself. When the right camera does
    /// not explain the reference's edges (smooth shading such as depth, defocus blur, a
    /// picture of a few pixels), the scene's pictures cannot convict a camera: the judge
    /// then still finds a right camera where it explains a picture (one sharper than the
    /// reference), and otherwise leaves the verdict to the image judgement.
    pub fn new(scene: Scene, reference: &RgbaImage) -> SceneJudge {
        let pictures = PictureJudge::new(&scene);
        let interior = pictures.candidates().interior(INTERIOR_MARGIN);
        let eye = EyeSearch::new(&scene);
        let judges = pictures.judge(reference).passed();
        let defocus = matches!(
            scene.camera().projection(),
            Projection::ThinLens(lens) if lens.aperture > 0.0
        );
        SceneJudge {
            scene,
            pictures,
            interior,
            eye,
            judges,
            defocus,
        }
    }

    /// Whether the right camera explains the reference's edges, so that the camera of the
    /// scene's pictures is judged (see [`SceneJudge::new`]).
    pub fn judges(&self) -> bool {
        self.judges
    }

    /// The catalogue's groups of entries this scene tells apart (see
    /// [`PictureJudge::entries`]).
    pub fn entries(&self) -> &[Vec<Mistake>] {
        self.pictures.entries()
    }
}

/// A catalogue entry in the words viewray-compare carries.
pub fn catalogue_entry(mistake: Mistake) -> CatalogueEntry {
    let entry = mistake.entry();
    CatalogueEntry {
        id: entry.id.to_owned(),
        looks: entry.looks.to_owned(),
        summary: entry.summary.to_owned(),
        fix: entry.fix.to_owned(),
        picture: entry.picture.to_owned(),
    }
}

impl CameraJudge for SceneJudge {
    fn size(&self) -> (u32, u32) {
        self.pictures.size()
    }

    fn judge(
        &self,
        picture: &RgbaImage,
        measure: &dyn Fn() -> Option<CameraMistake>,
    ) -> CameraFinding {
        if picture.dimensions() != self.size() {
            return CameraFinding::WrongSize {
                found: picture.dimensions(),
                expected: self.size(),
            };
        }
        let edges = PictureEdges::of(picture);
        let candidates = self.pictures.candidates();
        let judged = candidates
            .judge_edges(&edges)
            .expect("the picture is the maps' size");
        let verdict = self.pictures.verdict(&judged);
        // Where the reference's own edges are too weak to tell a camera, a picture the
        // right camera explains (sharper than the reference) is still right, but nothing
        // else convicts.
        if !self.judges && !verdict.passed() {
            return CameraFinding::Unjudged;
        }
        let right_eye = self.scene.camera().frame().e();
        let eye_moved = |moved: eye::MovedEye, right: f64| CameraFinding::EyeMoved {
            offset: moved.offset,
            sentence: eye::sentence(&moved, right_eye),
            agreement: moved.fit.agreement,
            right,
        };
        match verdict {
            CameraVerdict::Right { agreement } => CameraFinding::Right { agreement },
            CameraVerdict::Mistaken { explanation, right } => {
                // A moved eye that explains the picture clearly better than the best
                // entry is what the student did. As well as it is not enough: a picture
                // that both explain perfectly (a horizon alone, looking backwards) is the
                // entry's, which the lecture names.
                let entry = match &judged.verdict {
                    GeometryVerdict::Candidate(group) => group
                        .iter()
                        .map(|&k| judged.candidates[k].score)
                        .fold(0.0, f64::max),
                    _ => 0.0,
                };
                // An entry within the margin of a perfect score leaves a moved eye no
                // room to do better: the search is not run.
                let moved = (entry + CANDIDATE_MARGIN < 1.0)
                    .then(|| {
                        self.eye.search(
                            &self.scene,
                            &Seen {
                                candidates,
                                edges: &edges,
                                judged: &judged,
                                measured: None,
                            },
                        )
                    })
                    .flatten();
                match moved {
                    Some(moved) if moved.fit.score > entry + CANDIDATE_MARGIN => {
                        eye_moved(moved, right)
                    }
                    _ => CameraFinding::Mistaken {
                        entries: explanation
                            .mistakes
                            .iter()
                            .copied()
                            .map(catalogue_entry)
                            .collect(),
                        agreement: explanation.agreement,
                        right,
                    },
                }
            }
            CameraVerdict::WrongSize { found, expected } => {
                CameraFinding::WrongSize { found, expected }
            }
            CameraVerdict::Unexplained { right, .. } => {
                let measured = measure();
                let shift = measured.map(|m| m.shift);
                let seen = Seen {
                    candidates,
                    edges: &edges,
                    judged: &judged,
                    measured: shift,
                };
                match self.eye.search(&self.scene, &seen) {
                    Some(moved) => eye_moved(moved, right),
                    // A lens's picture blurred unlike the reference (more samples, or
                    // fewer) is explained by no sharp map: that convicts no camera.
                    None if self.defocus => CameraFinding::Unjudged,
                    None => CameraFinding::Unexplained { measured, right },
                }
            }
        }
    }

    fn interior(&self) -> &[bool] {
        &self.interior
    }
}
