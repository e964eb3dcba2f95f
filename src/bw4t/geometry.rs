//! Positions and axis-aligned rectangles (y grows downwards, containment is half-open).

use nalgebra::{Point2, Vector2};

/// A position in map units.
pub type Pos = Point2<f64>;

/// A displacement in map units.
pub type Vec2 = Vector2<f64>;

/// An axis-aligned rectangle `[min.x, max.x) x [min.y, max.y)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rect {
    pub min: Pos,
    pub max: Pos,
}

impl Rect {
    /// The rectangle with the given centre, width and height.
    pub fn centred(x: f64, y: f64, width: f64, height: f64) -> Rect {
        Rect {
            min: Pos::new(x - width / 2.0, y - height / 2.0),
            max: Pos::new(x + width / 2.0, y + height / 2.0),
        }
    }

    /// The centre point.
    pub fn centre(&self) -> Pos {
        nalgebra::center(&self.min, &self.max)
    }

    /// Half-open containment of a point: `min <= p < max` on both axes.
    pub fn contains(&self, p: &Pos) -> bool {
        self.min.x <= p.x && p.x < self.max.x && self.min.y <= p.y && p.y < self.max.y
    }

    /// Width and height.
    pub fn size(&self) -> Vec2 {
        self.max - self.min
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn containment_is_half_open() {
        let r = Rect::centred(5.0, 5.0, 10.0, 10.0);
        assert!(r.contains(&Pos::new(0.0, 0.0)));
        assert!(!r.contains(&Pos::new(10.0, 5.0)));
        assert!(!r.contains(&Pos::new(5.0, 10.0)));
        assert_eq!(r.centre(), Pos::new(5.0, 5.0));
    }
}
