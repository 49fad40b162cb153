"""Snooker equipment figures with their sources: the 12 ft table, its pockets, 52.5 mm balls (`Table.snooker()`).

Sources (figures carried over, cited; no text or code copied):

- WPBSA Official Rules of Snooker, Section 1 (Equipment), Rule 1 "The Standard Table":
  (a) the playing area inside the cushion faces is 11 ft 8 1/2 in x 5 ft 10 in, 3569 x 1778 mm
  (+- 13 mm); (c)(ii) the pocket openings follow the templates the WPBSA authorises; (d) the
  baulk line is 29 in (737 mm) from the face of the bottom cushion; (e) the D is a half circle
  in baulk centred on the middle of the baulk line, radius 11 1/2 in (292 mm); (f) the spots:
  black 12 3/4 in (324 mm) from the top cushion's face, blue midway between the top and bottom
  cushions, pink midway between blue and the top cushion, brown the middle of the baulk line,
  yellow and green the D's corners (yellow on the right seen from the baulk end). Rule 2
  "Balls": 52.5 mm diameter (+- 0.05 mm), a set equal in weight within 3 g. (As reproduced on
  forums.azbilliards.com "Rules of snooker to play" and balls.com "english snooker balls".)
- The WPBSA pocket templates themselves are not published (the templates "very secretly
  guarded": blog.betway.com "are the pockets on snooker tables really getting bigger", 2020).
  The mouths, jaw roundings, shelves and the cushion nose height are therefore those pooltool
  (ekiefl/pooltool, pooltool/objects/table/specs.py, `SnookerTableSpecs`) measured on a
  snooker table: corner mouth 0.083 m, middle 0.087 m; corner jaw radius 4 in, middle 2.5 in;
  corner pocket depth 0.036 m, middle 0.95 in; cushion height 0.028 m.
- The jaws' cut angles: 142 degrees at the corners, 104 at the middles, inside the ranges
  142-145 and 100-104 of polymorvic/deep-peep-snooker (src/utils/const.py).
- The ball's mass: the rules fix none (only the 3 g spread in a set); 142 g as
  polymorvic/deep-peep-snooker (src/utils/const.py) gives for a set.
"""

from __future__ import annotations

from .pocket_shape import INCH, PocketShape

SNOOKER_LENGTH, SNOOKER_WIDTH = 3.569, 1.778  # m, WPBSA S1 R1(a)
SNOOKER_BALL_RADIUS = 0.0525 / 2.0  # m, WPBSA S1 R2
SNOOKER_BALL_MASS = 0.142  # kg (deep-peep-snooker; the WPBSA fixes only a 3 g spread)
BAULK_LINE = 0.737  # m from the bottom (baulk) cushion's face, WPBSA S1 R1(d)
D_RADIUS = 0.292  # m, WPBSA S1 R1(e)
BLACK_SPOT_FROM_TOP = 0.324  # m from the top cushion's face, WPBSA S1 R1(f)(i)
CORNER_MOUTH, MIDDLE_MOUTH = 0.083, 0.087  # m between the jaw points (pooltool SnookerTableSpecs)
CUSHION_HEIGHT = 0.028  # m, the nose above the cloth (pooltool SnookerTableSpecs)
CORNER_POCKET = PocketShape(cut_angle=142.0, jaw_radius=4.0 * INCH, shelf=0.036)
MIDDLE_POCKET = PocketShape(cut_angle=104.0, jaw_radius=2.5 * INCH, shelf=0.95 * INCH)
