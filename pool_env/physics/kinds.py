"""The ids every module shares: motion states, state-row columns, event kinds, counters, exit codes.

Compiled code dispatches on these integers; Python code names them. Every other module
imports them from here (never re-derives them with `.index()` or writes the number).
"""

# Motion states of a ball (the state code stored beside each state row).
# AIRBORNE: in flight above the cloth (airborne.py), after an elevated cue or a bounce.
STATIONARY, SPINNING, SLIDING, ROLLING, POCKETED, AIRBORNE = 0, 1, 2, 3, 4, 5
STATE_NAMES = ("stationary", "spinning", "sliding", "rolling", "pocketed", "airborne")

# Columns of a ball's state row [x, y, vx, vy, wx, wy, wz, t0, z, vz] (motion.py explains the
# row): z is the centre's height above where it rests on the cloth (0 on the cloth), vz its
# vertical velocity; both are exact zeros for a ball on the cloth.
X, Y, VX, VY, WX, WY, WZ, T0, Z, VZ = range(10)
CUE = 0  # the cue ball's number: its row in every array of a layout
# The row's width: every row, history row (ROW_WIDTH + 1 with the state code) and scratch row.
ROW_WIDTH = 10

# Event kinds, in the order of their ids (`Result.event_arrays` holds the ids).
EVENT_KINDS = (
    "ball_ball", "ball_cushion", "ball_pocket",
    "sliding_rolling", "rolling_spinning", "rolling_stationary", "spinning_stationary",
    "sliding_stationary", "sliding_spinning",
    # A ball-ball contact resolved with the cloth's help (a pressed contact, settle.py, or a
    # gentle one that leaves a rolling ball rolling, motion.reroll): momentum is not conserved.
    "ball_ball_settle",
    # An airborne ball meets the slate (it bounces, or lands and slides on: airborne.py), and
    # one that leaves the table: over a rail (j the rail's row) or landing off the bed (j -1).
    "ball_table", "ball_off_table",
)
(BALL_BALL, BALL_CUSHION, BALL_POCKET,
 SLIDING_ROLLING, ROLLING_SPINNING, ROLLING_STATIONARY, SPINNING_STATIONARY,
 SLIDING_STATIONARY, SLIDING_SPINNING,
 BALL_BALL_SETTLE, BALL_TABLE, BALL_OFF_TABLE) = range(len(EVENT_KINDS))
# Kinds that are contacts between two balls (with or without the cloth's help).
BALL_BALL_KINDS = (BALL_BALL, BALL_BALL_SETTLE)
# The scheduler's placeholders while it looks for the earliest event: none found yet, and a
# motion transition (its kind is known only once transition.resolve has run).
NO_EVENT, TRANSITION = -1, -2

# Counters the event loop keeps (see Result.stats), in the order of their ids.
COUNTERS = (
    "ball_ball_predictions", "ball_ball_rejected",
    "ball_cushion_predictions", "ball_cushion_rejected",
    "ball_pocket_predictions", "ball_pocket_rejected",
    "transition_predictions", "resting_pairs_skipped",
    # Predictions involving an airborne ball (airborne.py): 0 for every level shot.
    "airborne_predictions",
)
C_BB, C_BB_REJ, C_CU, C_CU_REJ, C_PO, C_PO_REJ, C_TR, C_REST, C_AIR = range(len(COUNTERS))

# How a compiled loop ended: finished; hit the caller's event cap; ran out of output buffer
# (the caller retries with larger buffers: the simulation is deterministic); (fixed-step
# only) hit its cap on the number of frames; (engine.simulate_scene only) a ball is not where
# it may be, and nothing ran (simulate.check_on_table names the problem); (airborne balls) a
# ball came to rest on top of another, which the engine does not model (the pending event is
# kept one past the last, as for EVENT_CAP).
DONE, EVENT_CAP, BUFFER_FULL, STEP_CAP, MISPLACED, PERCHED = 0, 1, 2, 3, 4, 5
