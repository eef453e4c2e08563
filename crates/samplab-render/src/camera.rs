//! A perspective camera with an optional thin lens (Subr & Kautz 2013, Fig. 7's defocus).

use glam::DVec3;
use samplab::warp::concentric;

use crate::geometry::Ray;

/// A perspective camera given as Mitsuba's `lookat` and field of view.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    /// Eye position.
    pub eye: DVec3,
    /// A point the camera looks at.
    pub target: DVec3,
    /// The up direction.
    pub up: DVec3,
    /// Horizontal field of view in degrees (Mitsuba's default `fov_axis = x`).
    pub fov: f64,
    /// Lens radius (0: a pinhole).
    pub aperture: f64,
    /// Distance of the plane in focus, along the view direction.
    pub focus: f64,
    /// Mitsuba's `near_clip` and `far_clip`: what lies nearer than the first or farther
    /// than the second, in depth along the view direction, is not seen by camera rays
    /// (`[0, inf]` clips nothing).
    pub clip: [f64; 2],
}

/// A camera set up for one image size.
#[derive(Debug, Clone, Copy)]
pub struct Frame {
    eye: DVec3,
    forward: DVec3,
    /// Unit right and up (for the lens).
    right: DVec3,
    up: DVec3,
    /// Image-plane half extents at distance 1.
    half_w: f64,
    half_h: f64,
    aperture: f64,
    focus: f64,
    clip: [f64; 2],
}

impl Camera {
    /// The frame for a `width` x `height` image.
    pub fn frame(&self, width: usize, height: usize) -> Frame {
        let forward = (self.target - self.eye).normalize();
        let right = forward.cross(self.up).normalize();
        let up = right.cross(forward);
        let half_w = (0.5 * self.fov.to_radians()).tan();
        Frame {
            eye: self.eye,
            forward,
            right,
            up,
            half_w,
            half_h: half_w * height as f64 / width as f64,
            aperture: self.aperture,
            focus: self.focus,
            clip: self.clip,
        }
    }
}

impl Frame {
    /// The ray through film point (x, y) (both in [0, 1), y down), from lens sample `lens`
    /// (unit square, mapped to the lens disk concentrically) at shutter time `time`. The
    /// ray starts on the near clipping plane, as Mitsuba 3's perspective and thin-lens
    /// cameras start theirs; [`Frame::beyond_far`] says which of its hits are clipped.
    #[inline(always)]
    pub fn ray(&self, x: f64, y: f64, lens: [f64; 2], time: f64) -> Ray {
        let dir = self.forward + (2.0 * x - 1.0) * self.half_w * self.right + (1.0 - 2.0 * y) * self.half_h * self.up;
        let mut ray = if self.aperture <= 0.0 {
            Ray { origin: self.eye, dir, time }
        } else {
            let focus_point = self.eye + dir * self.focus;
            let (x, y) = concentric(lens[0], lens[1]);
            let origin = self.eye + self.aperture * (x * self.right + y * self.up);
            Ray { origin, dir: focus_point - origin, time }
        };
        if self.clip[0] > 0.0 {
            ray.origin += ray.dir * (self.clip[0] / self.depth_per_t());
        }
        ray
    }

    /// Whether a camera ray's hit at parameter `t` lies beyond the far clipping plane: the
    /// camera does not see it.
    #[inline(always)]
    pub fn beyond_far(&self, t: f64) -> bool {
        t * self.depth_per_t() > self.clip[1] - self.clip[0]
    }

    /// How far along the view direction a camera ray goes per unit of its parameter: its
    /// direction's component along the view (1 for a pinhole, whose rays reach the unit
    /// image plane at t = 1; the focus distance for a lens, whose rays reach the focus plane).
    #[inline(always)]
    fn depth_per_t(&self) -> f64 {
        if self.aperture <= 0.0 { 1.0 } else { self.focus }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_image_centre_looks_at_the_target_and_edges_span_the_fov() {
        let cam = Camera {
            eye: DVec3::new(0.0, 0.0, 5.0),
            target: DVec3::ZERO,
            up: DVec3::Y,
            fov: 90.0,
            aperture: 0.0,
            focus: 1.0,
            clip: [0.0, f64::INFINITY],
        };
        let f = cam.frame(200, 100);
        let centre = f.ray(0.5, 0.5, [0.5; 2], 0.0).dir.normalize();
        assert!((centre - DVec3::NEG_Z).length() < 1e-15);
        let right_edge = f.ray(1.0, 0.5, [0.5; 2], 0.0).dir.normalize();
        assert!((right_edge.angle_between(DVec3::NEG_Z).to_degrees() - 45.0).abs() < 1e-12);
        assert!(right_edge.x > 0.0, "image x runs to the right");
        assert!(f.ray(0.5, 0.0, [0.5; 2], 0.0).dir.y > 0.0, "image y runs down");
    }

    #[test]
    fn every_lens_ray_meets_the_focus_plane_at_the_same_point() {
        let cam = Camera {
            eye: DVec3::new(1.0, 2.0, 3.0),
            target: DVec3::ZERO,
            up: DVec3::Y,
            fov: 40.0,
            aperture: 0.3,
            focus: 2.5,
            clip: [0.0, f64::INFINITY],
        };
        let f = cam.frame(64, 64);
        let forward = (cam.target - cam.eye).normalize();
        let mut hits = Vec::new();
        for lens in [[0.1, 0.2], [0.9, 0.5], [0.5, 0.5]] {
            let r = f.ray(0.3, 0.7, lens, 0.0);
            let t = (cam.focus - (r.origin - cam.eye).dot(forward)) / r.dir.dot(forward);
            hits.push(r.at(t));
        }
        assert!((hits[0] - hits[1]).length() < 1e-12 && (hits[0] - hits[2]).length() < 1e-12);
    }
}
