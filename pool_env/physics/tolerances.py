"""Every tolerance of the simulator, each with why it has its value (SI units).

They sit between two walls: far below anything physical (the hard-case suite drives balls at
1e-6 m/s and checks positions to 1 nm) and far above the round-off of the quantity they
guard (a contact computed in float64 on a 2 m table is good to about 1e-16 m).
"""

# --- objects on the table ---------------------------------------------------------------
# Balls may touch within this (m): a frozen rack computed in floating point sits a few ulps
# either side of exact contact, and a ball may rest this close to a rail.
CONTACT_TOLERANCE = 1e-9
# Table geometry: a pocket centre this close (m) to a rail's line, or a mouth this close to a
# rail's end or another mouth, is on it (round-off in the coordinates a user types).
PLACEMENT_SLACK = 1e-12

# --- motion -------------------------------------------------------------------------------
# Speeds (m/s) and spins (rad/s) below these are exact zeros: round-off left by a collision
# or a transition, six orders of magnitude below the slowest ball the hard cases drive.
EPS_V = 1e-12
EPS_W = 1e-10
# A contact that leaves a rolling ball a slip that sliding would remove within this time
# (s) is gentle: the slide is taken at once (motion.reroll); its path then differs from the
# straight one by under a nanometre.
GENTLE_TIME = 1e-5
# A ball meeting the slate bounces only if the bounce would lift it this high (m): lower
# rebounds end the bouncing and the ball slides on (pooltool's FrictionalInelasticTable
# min_bounce_height, 5 mm). It also bounds the number of bounces: heights fall by e_t^2 a bounce.
BOUNCE_STOP_HEIGHT = 5e-3
# Slack (m) added to a ball's travel bound and to the broad phase's clearance, so a bound
# computed with round-off never rejects a contact that happens.
REACH_SLACK = 1e-12
# A squared length more than this fraction from a threshold's square decides a comparison of
# the length with the threshold without the square root (geometry.longer_than,
# predict.out_of_reach): a million times the round-off of a sum of squares, so the answer is
# the square root's, to the bit.
CLEAR = 1e-9
# Added to the distance beyond which predict.outside_travel rejects a pocket before the broad
# phase: far above the round-off of distances on a table (1e-15 m), far below any gap that
# matters, so that test never rejects what the broad phase would let through.
FAR_MARGIN = 1e-9

# --- contact detection (roots.first_entry and its callers) ---------------------------------
# Contacts approaching slower than this (m/s) are tangent touches, not collisions: far below
# anything physical and far above the round-off in a relative velocity, so a resolved pair
# is never re-detected at once.
MIN_APPROACH = 1e-12
# A slow crossing (approach below MIN_APPROACH) is a graze unless the paths go on to overlap
# by more than this (m); it is also how deep a pressed pair may sink before it is resolved.
MIN_DEPTH = 1e-10
# A root within this many MIN_DEPTHs below zero is touching (in contact up to round-off);
# deeper is a ball past a rail's line beside a pocket mouth, where the contact is at f = 0.
TOUCH_DEPTHS = 10.0
# Contact times of pairs starting farther apart than this (m) are polished on the gap
# itself (geometry.distance_entry); touching pairs' contacts are not at gap zero.
POLISH_GAP = 1e-6
# Newton-bisection iterations of the root finder: it converges in a handful; the cap only
# guards against a pathological polynomial.
ROOT_MAX_ITER = 100

# --- simultaneous contacts (contacts.py) ---------------------------------------------------
# Contacts predicted within this (s) of the event being resolved are resolved with it as
# one group, so the order of contacts simultaneous up to round-off does not matter.
GROUP_WINDOW = 1e-12
# A pair that meets again within this (s) is caught in a cascade: rows of balls "touching"
# in floating point are 1e-16 m apart, so a cascade's contacts are that many seconds apart.
LOOP_WINDOW = 1e-9
# Balls this close (m) count as touching when a cluster or a pack is gathered.
TOUCH_GAP = 1e-9
# The projected Gauss-Seidel solve of a contact group stops when a sweep changes no velocity
# by more than this, relative to the largest speed (round-off level), or after this many
# sweeps (a group of a full rack converges in tens).
GROUP_TOL = 1e-15
GROUP_SWEEPS = 1000
# Two directions closer than this (sine of the angle between them) are one: a ball's contact
# normals in a group (ball_ball.resolve_group), a path and its acceleration (broad phase).
PARALLEL_SINE = 1e-12

# --- pressed contacts (settle.py) ------------------------------------------------------------
# A contact is pressed if a bounce at its approach speed would rise less than this (m)
# before the accelerations closed the gap again: a tenth of a micron is no bounce at all
# (about the balls' elastic deformation under a light push).
SETTLE_HEIGHT = 1e-7
# A pair sunk this deep (m) into each other rolls on together: repeated settles each let it
# sink up to MIN_DEPTH deeper, so this keeps overlaps below 1 nm.
SETTLE_OVERLAP = 5e-10
# Residual pressing weaker than this (m/s^2) is round-off.
PRESS_TOL = 1e-12
