//! The scene's camera judge that `viewray compare` and `viewray grade` hand to
//! viewray-compare ([`viewray_compare::CameraJudge`]): prepared once per scene, it judges
//! a picture's edges against the right camera and the catalogue's mistaken ones, looks
//! for a moved eye when none explains them, and answers in the catalogue's words.

use viewray_camera::Mistake;
use viewray_compare::{
    CameraFinding, CameraJudge, CameraMistake, CatalogueEntry, PictureEdges, RgbaImage,
};
use viewray_scene::Scene;

use crate::eye::{self, EyeSearch};
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
}

impl SceneJudge {
    /// Prepares `scene` (loaded at the reference image's size): labels it through its
    /// camera and every catalogue entry that fits it ([`PictureJudge::new`]).
    pub fn new(scene: Scene) -> SceneJudge {
        let pictures = PictureJudge::new(&scene);
        let interior = pictures.candidates().interior(INTERIOR_MARGIN);
        let eye = EyeSearch::new(&scene);
        SceneJudge {
            scene,
            pictures,
            interior,
            eye,
        }
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
        match self.pictures.verdict(&judged) {
            CameraVerdict::Right { agreement } => CameraFinding::Right { agreement },
            CameraVerdict::Mistaken { explanation, right } => CameraFinding::Mistaken {
                entries: explanation
                    .mistakes
                    .iter()
                    .copied()
                    .map(catalogue_entry)
                    .collect(),
                agreement: explanation.agreement,
                right,
            },
            CameraVerdict::WrongSize { found, expected } => {
                CameraFinding::WrongSize { found, expected }
            }
            CameraVerdict::Unexplained { right, .. } => {
                let measured = measure();
                let shift = measured.map(|m| m.shift);
                match self
                    .eye
                    .search(&self.scene, candidates, &edges, &judged, shift)
                {
                    Some(moved) => CameraFinding::EyeMoved {
                        offset: moved.offset,
                        sentence: eye::sentence(&moved, self.scene.camera().frame().e()),
                        agreement: moved.fit.agreement,
                        right,
                    },
                    None => CameraFinding::Unexplained { measured, right },
                }
            }
        }
    }

    fn interior(&self) -> &[bool] {
        &self.interior
    }
}
