"""The perception's pure parts: back-projection, the block tracker, the literal confidences."""

import numpy as np
import pytest

from semgoal_core.geometry import TABLE_TOP
from semgoal_core.settling import REST_SPEED
from semgoal_core.vocabulary import BLOCK_HALF_SIZE, LAYOUTS, SCENES, Literal, fallen_blocks
from semgoal_perception.estimator import Detection, detections
from semgoal_perception.geometry import PinholeCamera
from semgoal_perception.semantics import SemanticEstimator
from semgoal_perception.tracker import DOUBT_FRAMES, HELD_HANG, LOST_FRAMES, SIGMA_HELD, BlockTracker, Hand, Track, TrackStatus, in_hand

LOOKING_DOWN = np.array([[1.0, 0, 0, 1.3], [0, -1.0, 0, 0.75], [0, 0, -1.0, 1.4], [0, 0, 0, 1.0]])
"""An optical frame 1 m over the table top (z = 0.4), looking straight down."""


def test_world_points_project_back_onto_their_pixels() -> None:
    camera = PinholeCamera(140.0, 140.0, 79.5, 59.5, LOOKING_DOWN)
    depth = np.random.default_rng(0).uniform(0.8, 1.0, (120, 160)).astype(np.float32)
    depth[3, 4] = 0.0
    points, valid = camera.world_points(depth)
    assert not valid[3, 4] and valid.sum() == depth.size - 1
    v, u = np.nonzero(valid)
    assert np.allclose(camera.project(points[valid]), np.column_stack([u, v]), atol=1e-3)
    assert np.allclose(points[..., 2][valid], 1.4 - depth[valid], atol=1e-5)


def test_a_block_is_its_pixels_median_vote_and_a_sliver_is_not_seen() -> None:
    labels = np.zeros((20, 20), dtype=np.int64)
    labels[2:8, 2:8] = 1  # 36 pixels of colour 0
    labels[15, 15:17] = 3  # 2 pixels of colour 2: too few
    votes = np.zeros((20, 20, 3))
    votes[labels == 1] = [1.30, 0.70, 0.425]
    votes[3, 3] = [9.0, 9.0, 9.0]  # one wild vote does not move the median
    found = detections(labels.reshape(-1), votes.reshape(-1, 3))
    assert [d.colour for d in found] == [0]
    assert np.allclose(found[0].centre, [1.30, 0.70, 0.425]) and found[0].pixels == 36


def seen(colour: int, centre) -> Detection:
    return Detection(colour, np.asarray(centre, dtype=float), np.full(3, 0.0015), 60)


GRIP_AWAY, STILL = np.array([1.3, 0.6, 0.7]), np.zeros(3)
AWAY = [Hand(GRIP_AWAY, STILL, 0.1)]
"""The one arm's hand, open and far above the blocks."""
TABLETOP_BIN = SCENES["tabletop"].bin
ON_BIN_FLOOR = TABLE_TOP + TABLETOP_BIN.floor_thickness + BLOCK_HALF_SIZE
"""The height of a block's centre lying on the tabletop bin's floor."""


def test_a_resting_block_seen_with_millimetre_noise_reads_as_at_rest() -> None:
    tracker, rng = BlockTracker([0]), np.random.default_rng(1)
    speeds = []
    for _ in range(100):
        track = tracker.update([seen(0, np.array([1.3, 0.7, 0.425]) + rng.normal(0, 0.001, 3))], AWAY)[0]
        speeds.append(np.linalg.norm(track.velocity))
    assert max(speeds[10:]) < REST_SPEED
    assert np.linalg.norm(track.position - [1.3, 0.7, 0.425]) < 0.002


def test_a_moving_block_reads_as_moving() -> None:
    tracker = BlockTracker([0])
    for step in range(30):
        track = tracker.update([seen(0, [1.2 + 0.004 * step, 0.7, 0.425])], AWAY)[0]
    assert np.allclose(track.velocity, [0.1, 0.0, 0.0], atol=0.01)  # 4 mm per 0.04 s step


def test_a_hidden_block_keeps_its_estimate_with_growing_uncertainty_then_is_lost_not_dropped() -> None:
    tracker = BlockTracker([0, 1])
    tracker.update([seen(0, [1.3, 0.7, 0.425]), seen(1, [1.2, 0.8, 0.425])], AWAY)
    sigmas = []
    for _ in range(LOST_FRAMES - 1):
        track = tracker.update([seen(1, [1.2, 0.8, 0.425])], AWAY)[0]
        assert track.status == TrackStatus.OCCLUDED
        sigmas.append(track.sigma[0])
    assert np.allclose(track.position, [1.3, 0.7, 0.425]) and np.all(np.diff(sigmas) >= 0) and sigmas[-1] > sigmas[0]
    assert tracker.update([], AWAY)[0].status == TrackStatus.LOST
    assert np.allclose(tracker.tracks[0].position, [1.3, 0.7, 0.425])
    assert tracker.update([seen(0, [1.31, 0.7, 0.425])], AWAY)[0].status == TrackStatus.VISIBLE


def test_a_block_in_the_closed_hand_follows_the_grip_when_unseen() -> None:
    tracker, grip = BlockTracker([0]), np.array([1.3, 0.7, 0.43])
    tracker.update([seen(0, [1.3, 0.7, 0.425])], [Hand(grip, STILL, 0.05)])  # fingers closed on it
    for _ in range(10):
        grip = grip + np.array([0.0, 0.0, 0.01])
        track = tracker.update([], [Hand(grip, np.array([0.0, 0.0, 0.25]), 0.05)])[0]
    assert track.status == TrackStatus.HELD and np.allclose(track.position, grip + np.array([0, 0, HELD_HANG]))
    assert np.allclose(track.velocity, [0, 0, 0.25]) and track.sigma.min() >= SIGMA_HELD


def test_a_block_seen_in_the_hand_moves_with_the_hand_at_once_and_slips_in_it_as_seen() -> None:
    """Filtered as a free block, a carried block lagged the hand by centimetres; it moves with the hand's kinematics,
    and its offset in the hand follows what the camera sees of it there (it slips and swings), never across the fingers
    (they centre it)."""
    tracker, rest = BlockTracker([0]), np.array([1.3, 0.7, 0.425])
    for _ in range(3):
        tracker.update([seen(0, rest)], AWAY)
    grip = rest + np.array([0.0, 0.0, 0.014])
    tracker.update([seen(0, rest)], [Hand(grip, STILL, 0.05)])  # the fingers close
    slip = np.array([0.01, 0.004, HELD_HANG])  # 1 cm along x, seen 4 mm off across the fingers
    for _ in range(12):
        grip = grip + np.array([0.02, 0.0, 0.01])
        track = tracker.update([seen(0, grip + slip)], [Hand(grip, np.array([0.5, 0, 0.25]), 0.05)])[0]
    assert track.status == TrackStatus.VISIBLE and track.hand == 0 and np.allclose(track.velocity, [0.5, 0, 0.25])
    assert np.allclose(track.position, grip + np.array([0.01, 0.0, HELD_HANG]), atol=5e-4)


def test_a_grasped_block_rests_where_it_was_until_it_hangs_below_the_rising_grip() -> None:
    tracker, rest = BlockTracker([0]), np.array([1.3, 0.7, 0.425])
    tracker.update([seen(0, rest)], AWAY)
    heights = []
    for rise in (0.0, 0.005, 0.01, 0.015, 0.02, 0.03, 0.05, 0.02):  # closes at the block's centre, lifts, lowers
        grip = rest + np.array([0.002, 0.0, rise])
        heights.append(tracker.update([], [Hand(grip, STILL, 0.05)])[0].position[2] - rest[2])
    assert np.allclose(heights, [0, 0, 0, 0, 0.002, 0.012, 0.032, 0.002])
    assert np.allclose(tracker.tracks[0].position[:2], rest[:2])


def lifted_unseen(tracker: BlockTracker) -> Hand:
    """Block 0 grasped at rest and lifted 10 cm, out of sight; the hand holding it."""
    grip = np.array([1.3, 0.7, 0.43])
    tracker.update([seen(0, [1.3, 0.7, 0.425])], [Hand(grip, STILL, 0.05)])
    lifted = Hand(grip + np.array([0, 0, 0.1]), STILL, 0.05)
    tracker.update([], [lifted])
    assert tracker.tracks[0].status == TrackStatus.HELD
    return lifted


def test_a_held_block_seen_far_from_its_hand_while_the_fingers_stay_closed_on_it_has_left_it_once_that_persists() -> None:
    """One stray vote 18 cm away once took a lifted block out of the fingers, and the expert let it fall."""
    tracker = BlockTracker([0])
    lifted = lifted_unseen(tracker)
    for _ in range(DOUBT_FRAMES - 1):
        track = tracker.update([seen(0, [1.35, 0.7, 0.425])], [lifted])[0]
        assert track.hand == 0 and np.allclose(track.position, lifted.position + np.array([0, 0, HELD_HANG]))
    track = tracker.update([seen(0, [1.35, 0.7, 0.425])], [lifted])[0]  # it persists: it did fall
    assert track.hand is None and track.status == TrackStatus.VISIBLE and np.allclose(track.position, [1.35, 0.7, 0.425])


def test_a_held_block_seen_far_from_fingers_closed_past_its_width_has_left_them_at_once() -> None:
    tracker = BlockTracker([0])
    lifted = lifted_unseen(tracker)
    track = tracker.update([seen(0, [1.35, 0.7, 0.425])], [lifted._replace(opening=0.01)])[0]
    assert track.hand is None and track.status == TrackStatus.VISIBLE and np.allclose(track.position, [1.35, 0.7, 0.425])


def test_a_block_seen_slipped_to_the_fingers_ends_stays_in_the_hand() -> None:
    """Votes of a block slipped 2 cm along the fingers, 1 cm off themselves, drew it past holding's 3 cm, and the
    tracker let it go onto the table while it rode in the hand."""
    tracker = BlockTracker([0])
    lifted = lifted_unseen(tracker)
    for _ in range(10):
        track = tracker.update([seen(0, lifted.position + np.array([0.035, 0.0, HELD_HANG]))], [lifted])[0]
        assert track.hand == 0 and in_hand(track.position, lifted.position, lifted.opening)
    assert track.position[0] > lifted.position[0] + 0.02


def test_a_block_lifted_between_two_frames_is_in_the_hand_and_follows_it() -> None:
    """Lifted 6 to 9 cm between two frames, a block was never taken as held (its filtered centre lagged under the grip),
    or was taken with its offset from where it had rested, out of the hand's reach, and let go in mid-air."""
    rest = np.array([1.3, 0.7, 0.425])
    up = np.array([0.0, 0.0, 1.0])
    for first_grip, first_seen in ((rest + 0.06 * up, rest + 0.048 * up),  # its filter still within reach
                                   (rest + 0.1 * up, rest + 0.09 * up)):  # beyond: seen in the hand
        tracker = BlockTracker([0])
        for _ in range(3):
            tracker.update([seen(0, rest)], AWAY)
        grip = first_grip
        track = tracker.update([seen(0, first_seen)], [Hand(grip, np.array([0.0, 0.0, 0.5]), 0.048)])[0]
        assert track.hand == 0
        for _ in range(5):
            grip = grip + np.array([0.0, 0.02, 0.03])
            track = tracker.update([seen(0, grip + np.array([0.0, 0.0, HELD_HANG - 0.004]))], [Hand(grip, STILL, 0.048)])[0]
            assert track.hand == 0 and in_hand(track.position, grip, 0.048)
        assert abs(track.position[2] - (grip[2] + HELD_HANG - 0.004)) < 0.003


def test_two_blocks_misread_as_each_other_keep_their_places() -> None:
    """Lifted high in the hand, a yellow block read as orange while orange on the table read as yellow: each took the
    other's place, and the hand seemed to hold orange."""
    tracker = BlockTracker([0, 1])
    lifted = lifted_unseen(tracker)  # block 0 in the hand
    orange = np.array([1.2, 0.95, 0.435])
    tracker.update([seen(1, orange)], [lifted])
    for _ in range(2 * DOUBT_FRAMES):
        held, other = tracker.update([seen(1, lifted.position + np.array([0.0, 0.0, HELD_HANG])), seen(0, orange)],
                                     [lifted]).values()
        assert held.hand == 0 and np.allclose(held.position, lifted.position + np.array([0, 0, HELD_HANG]))
        assert other.hand is None and np.allclose(other.position, orange)


def test_fingers_closing_on_a_block_off_their_centre_centre_it_between_them() -> None:
    tracker, rest = BlockTracker([0]), np.array([1.3, 0.7, 0.425])
    tracker.update([seen(0, rest)], AWAY)
    grip = rest + np.array([0.004, -0.02, 0.005])  # 2 cm off in y, the axis the fingers close on
    track = tracker.update([], [Hand(grip, STILL, 0.05)])[0]
    assert track.hand == 0 and np.allclose(track.position[:2], [rest[0], grip[1]])


def test_no_block_lies_under_the_table_top_but_one_beyond_its_edge_can() -> None:
    """Votes pushed into the table by the fingers over a block put it 14 mm under the table's top, lower than the hand
    can reach, and the hand never closed on it."""
    tracker = BlockTracker([0, 1])
    tracker.update([seen(0, [1.3, 0.7, 0.411]), seen(1, [1.3, 1.15, 0.2])], AWAY)
    assert np.isclose(tracker.tracks[0].position[2], TABLE_TOP + BLOCK_HALF_SIZE)
    assert np.isclose(tracker.tracks[1].position[2], 0.2)


def test_a_block_last_seen_falling_beyond_the_table_is_on_the_floor_and_has_fallen() -> None:
    """Knocked off the table and last seen 7 cm under its top, a block stayed in mid-air, and the hand tried to pick it
    there for 150 steps."""
    tracker = BlockTracker([0, 1])
    tracker.update([seen(0, [0.99, 0.71, 0.33]), seen(1, [1.2, 0.7, 0.425])], AWAY)
    positions = tracker.arrays()[0]
    assert fallen_blocks(["red", "green"], positions, TABLE_TOP) == []
    tracker.update([seen(1, [1.2, 0.7, 0.425])], AWAY)  # unseen now
    positions = tracker.arrays()[0]
    assert np.allclose(positions[0], [0.99, 0.71, BLOCK_HALF_SIZE]) and np.allclose(positions[1], [1.2, 0.7, 0.425])
    assert fallen_blocks(["red", "green"], positions, TABLE_TOP) == ["red"]


def test_a_block_in_the_other_arms_hand_follows_that_hand_and_goes_back_to_the_table_when_let_go() -> None:
    tracker, grip = BlockTracker([0, 1]), np.array([1.3, 0.9, 0.43])
    tracker.update([seen(0, [1.3, 0.9, 0.425]), seen(1, [1.2, 0.7, 0.425])], [*AWAY, Hand(grip, STILL, 0.05)])
    assert tracker.tracks[0].hand == 1 and tracker.tracks[1].hand is None
    for _ in range(10):  # the second arm lifts it out of sight; the first arm's hand stays away
        grip = grip + np.array([0.0, 0.01, 0.01])
        track = tracker.update([seen(1, [1.2, 0.7, 0.425])], [*AWAY, Hand(grip, np.array([0.0, 0.25, 0.25]), 0.05)])[0]
    assert track.status == TrackStatus.HELD and np.allclose(track.position, grip + np.array([0, 0, HELD_HANG]))
    assert np.allclose(track.velocity, [0, 0.25, 0.25])
    track = tracker.update([seen(0, [1.3, 1.0, 0.425])], [*AWAY, Hand(grip + np.array([0, 0, 0.1]), STILL, 0.1)])[0]
    assert track.status == TrackStatus.VISIBLE and track.hand is None and track.grip_offset is None


def test_a_resting_block_no_hand_is_near_does_not_jump_to_a_far_detection_until_it_persists() -> None:
    """The arm's blue links near another block have read as the blue block for a few frames."""
    tracker, rest, far = BlockTracker([0]), np.array([1.3, 0.7, 0.425]), np.array([1.3, 0.95, 0.425])
    for _ in range(3):
        tracker.update([seen(0, rest)], AWAY)
    for _ in range(DOUBT_FRAMES - 1):
        track = tracker.update([seen(0, far)], [Hand(far + np.array([0.0, 0.0, 0.05]), STILL, 0.08)])[0]
        assert np.allclose(track.position, rest) and track.status == TrackStatus.OCCLUDED
    track = tracker.update([seen(0, far)], AWAY)[0]  # it persists: the block did move (fell, was knocked)
    assert np.allclose(track.position, far) and np.allclose(track.velocity, 0) and track.status == TrackStatus.VISIBLE


def test_a_block_a_hand_is_near_follows_its_detection_at_once() -> None:
    tracker, rest = BlockTracker([0]), np.array([1.3, 0.7, 0.425])
    tracker.update([seen(0, rest)], AWAY)
    pushed = rest + np.array([0.08, 0.0, 0.0])
    track = tracker.update([seen(0, pushed)], [Hand(rest + np.array([0.05, 0.0, 0.03]), STILL, 0.08)])[0]
    assert track.status == TrackStatus.VISIBLE and track.position[0] > rest[0] + 0.04


def test_a_never_seen_block_stays_unknown() -> None:
    tracker = BlockTracker([0, 1])
    tracker.update([seen(1, [1.2, 0.8, 0.425])], AWAY)
    assert tracker.tracks[0].status == TrackStatus.NEVER_SEEN and np.isnan(tracker.tracks[0].position).all()


@pytest.fixture
def two_blocks() -> SemanticEstimator:
    return SemanticEstimator(LAYOUTS["two_blocks"])


def confidence_of(estimator: SemanticEstimator, literal: Literal, positions, sigma: float) -> tuple[bool, float]:
    vector, confidence = estimator.estimate(np.asarray(positions, dtype=float), np.full((2, 3), sigma),
                                            GRIP_AWAY, 0.1, np.ones(2, dtype=bool))
    entry = estimator.layout.index(literal)
    return bool(vector[entry]), float(confidence[entry])


def test_holding_is_in_either_hand(two_blocks) -> None:
    positions, sigmas, present = np.array([[1.3, 0.9, 0.6], [1.3, 0.7, 0.425]]), np.full((2, 3), 0.002), np.ones(2, bool)
    held = two_blocks.layout.index(Literal("holding", ("red",)))
    vector, _ = two_blocks.estimate(positions, sigmas, GRIP_AWAY, 0.1, present)
    assert not vector[held]
    vector, confidence = two_blocks.estimate(positions, sigmas, GRIP_AWAY, 0.1, present,
                                             other_hands=[(np.array([1.3, 0.9, 0.605]), 0.05)])
    assert vector[held] and confidence[held] == 1.0


def test_a_literal_far_from_its_threshold_is_certain_and_one_on_it_is_not(two_blocks) -> None:
    close = Literal("close", ("red", "green"))
    assert confidence_of(two_blocks, close, [[1.3, 0.7, 0.425], [1.3, 0.75, 0.425]], 0.002) == (True, 1.0)
    assert confidence_of(two_blocks, close, [[1.3, 0.7, 0.425], [1.3, 0.95, 0.425]], 0.002) == (False, 1.0)
    value, confidence = confidence_of(two_blocks, close, [[1.3, 0.7, 0.425], [1.3, 0.7999, 0.425]], 0.002)
    assert value and 0.3 < confidence < 0.8


def test_a_literal_of_a_block_never_seen_has_no_confidence(two_blocks) -> None:
    value, confidence = confidence_of(two_blocks, Literal("close", ("red", "green")),
                                      [[np.nan] * 3, [1.3, 0.75, 0.425]], 0.002)
    assert (value, confidence) == (False, 0.0)


def carried_then_let_go(tracker: BlockTracker, start, over, others=()) -> Track:
    """Block 0 grasped at ``start``, carried unseen to 3 cm above ``over``, and let go there, still unseen (the open
    hand hides it); ``others``: the other blocks' detections, every frame."""
    start, over = np.asarray(start, dtype=float), np.asarray(over, dtype=float)
    grasp, up = start + np.array([0.0, 0.0, 0.005]), np.array([0.0, 0.0, 0.12])
    tracker.update([seen(0, start), *others], [Hand(grasp, STILL, 0.05)])
    path = np.linspace(grasp + up, over + np.array([0.0, 0.0, 0.03 - HELD_HANG]), 10)
    for grip in path:
        track = tracker.update(list(others), [Hand(grip, STILL, 0.05)])[0]
        assert track.status == TrackStatus.HELD
    return tracker.update(list(others), [Hand(path[-1], STILL, 0.09)])[0]


def test_a_block_let_go_unseen_falls_onto_the_bins_floor() -> None:
    """Let go into a crowded bin, under the open hand, a block stayed where the hand had held it, above the rim."""
    tracker = BlockTracker([0], bin_geometry=TABLETOP_BIN)
    over = np.array([*TABLETOP_BIN.center, 0.46])
    track = carried_then_let_go(tracker, [1.1, 0.7, 0.425], over)
    assert track.hand is None and np.allclose(track.position, [*over[:2], ON_BIN_FLOOR]) and np.allclose(track.velocity, 0)
    assert TABLETOP_BIN.contains(track.position[None], TABLE_TOP)[0]


def test_a_block_let_go_unseen_lands_on_the_block_under_it_or_on_the_table() -> None:
    below = np.array([1.3, 0.7, 0.425])
    tracker = BlockTracker([0, 1])
    track = carried_then_let_go(tracker, [1.1, 0.7, 0.425], below + np.array([0.01, 0.0, 0.05]), [seen(1, below)])
    assert np.allclose(track.position, below + np.array([0.01, 0.0, 2 * BLOCK_HALF_SIZE]))
    tracker = BlockTracker([0, 1])
    track = carried_then_let_go(tracker, [1.1, 0.7, 0.425], below + np.array([0.06, 0.0, 0.05]), [seen(1, below)])
    assert np.allclose(track.position, [1.36, 0.7, TABLE_TOP + BLOCK_HALF_SIZE])


def test_a_block_let_go_with_its_estimate_sunk_into_the_block_under_it_lands_on_that_block() -> None:
    """Green, let go onto red with its estimate 2 cm low (its bottom 2 cm inside red's top), had fallen to the table,
    inside red, and the planner read red on green (Swap-2 from the camera)."""
    below = np.array([1.3, 0.7, 0.425])
    tracker = BlockTracker([0, 1])
    track = carried_then_let_go(tracker, [1.1, 0.7, 0.425], below + np.array([0.01, 0.0, 0.0]), [seen(1, below)])
    assert np.allclose(track.position, below + np.array([0.01, 0.0, 2 * BLOCK_HALF_SIZE]))


def test_a_block_let_go_lower_than_a_neighbours_top_lands_beside_it() -> None:
    """Let go 1 cm above the bin's floor over a neighbour's edge, a block stayed there, neither on the floor nor on the
    neighbour, where ``in_bin`` was unsure."""
    neighbour = np.array([*TABLETOP_BIN.center, ON_BIN_FLOOR])
    tracker = BlockTracker([0, 1], bin_geometry=TABLETOP_BIN)
    over = neighbour + np.array([0.03, 0.0, -0.02])  # let go with its centre 1 cm above its place on the floor
    track = carried_then_let_go(tracker, [1.1, 0.7, 0.425], over, [seen(1, neighbour)])
    assert np.allclose(track.position, [*over[:2], ON_BIN_FLOOR])


def test_a_block_let_go_off_a_blocks_top_face_tips_off_beside_it() -> None:
    """Let go 3 cm off a block's centre in a crowded bin, a block slid off it onto the floor, while its estimate stayed
    on top, above the rim."""
    below = np.array([*TABLETOP_BIN.center, ON_BIN_FLOOR])
    for off, lands in ((0.015, below + np.array([0.0, 0.015, 2 * BLOCK_HALF_SIZE])),  # over its top face: on it
                       (0.03, below + np.array([0.0, 2 * BLOCK_HALF_SIZE, 0.0]))):  # beyond: beside it, on the floor
        tracker = BlockTracker([0, 1], bin_geometry=TABLETOP_BIN)
        track = carried_then_let_go(tracker, [1.1, 0.7, 0.425], below + np.array([0.0, off, 0.05]), [seen(1, below)])
        assert np.allclose(track.position, lands)


def test_a_block_that_would_jump_into_another_block_seen_there_is_that_block_misread() -> None:
    """Part of a red block read as orange, 4 cm from red, took orange's track there while the hand over orange hid it."""
    tracker, orange, red = BlockTracker([0, 1]), np.array([1.15, 0.59, 0.425]), np.array([1.37, 0.68, 0.425])
    tracker.update([seen(0, orange), seen(1, red)], AWAY)
    hand_over_orange = [Hand(orange + np.array([0.0, 0.0, 0.02]), STILL, 0.08)]
    for _ in range(DOUBT_FRAMES + 2):
        tracks = tracker.update([seen(0, red - np.array([0.035, 0.0, 0.0])), seen(1, red)], hand_over_orange)
        assert np.allclose(tracks[0].position, orange) and tracks[0].status == TrackStatus.OCCLUDED
    assert np.allclose(tracks[1].position, red, atol=1e-3)
    moved = orange + np.array([0.06, 0.0, 0.0])  # the fingers did push it: seen there, apart from red, it is believed
    track = tracker.update([seen(0, moved), seen(1, red)], hand_over_orange)[0]
    assert track.status == TrackStatus.VISIBLE and track.position[0] > orange[0] + 0.03


def test_a_lost_block_is_not_taken_to_another_blocks_place_by_stray_votes_there() -> None:
    """Pink in a full bin's far corner, read as background for good, was lost; eight pink votes on purple beside it
    took pink's track there, and the expert put yellow onto pink."""
    tracker = BlockTracker([0, 1], bin_geometry=TABLETOP_BIN)
    pink, purple = np.array([1.44, 1.006, ON_BIN_FLOOR]), np.array([1.279, 1.01, ON_BIN_FLOOR])
    tracker.update([seen(0, pink), seen(1, purple)], AWAY)
    for _ in range(LOST_FRAMES):
        tracker.update([seen(1, purple)], AWAY)
    assert tracker.tracks[0].status == TrackStatus.LOST
    for _ in range(DOUBT_FRAMES + 2):
        stray = Detection(0, purple + np.array([0.001, 0.011, -0.013]), np.full(3, 0.0015), 8)
        tracks = tracker.update([stray, seen(1, purple)], AWAY)
        assert np.allclose(tracks[0].position, pink) and tracks[0].status == TrackStatus.LOST
    moved = np.array([1.2, 0.9, ON_BIN_FLOOR])  # seen apart from every other block, it is found again at once
    assert tracker.update([seen(0, moved), seen(1, purple)], AWAY)[0].status == TrackStatus.VISIBLE


def test_a_block_standing_on_another_does_not_sink_into_it_while_the_fingers_come_down_on_it() -> None:
    """The fingers coming down on a tower's top block hide its top and push its votes down: its estimate sank 4 cm into
    the block under it, and the hand, sent there, pressed on the tower until it fell."""
    tracker = BlockTracker([0, 1, 2])
    bottom = np.array([1.26, 0.62, TABLE_TOP + BLOCK_HALF_SIZE])
    up = np.array([0.0, 0.0, 2 * BLOCK_HALF_SIZE])
    middle, top = bottom + up, bottom + 2 * up
    tracker.update([seen(0, bottom), seen(1, middle), seen(2, top)], AWAY)
    hand = [Hand(top + np.array([0.0, 0.0, 0.06]), STILL, 0.1)]  # open, coming down
    for sunk in np.linspace(0.0, 0.04, 10):
        tracks = tracker.update([seen(0, bottom), seen(1, middle), seen(2, top - np.array([0.0, 0.0, sunk]))], hand)
    assert np.isclose(tracks[2].position[2], tracks[1].position[2] + 2 * BLOCK_HALF_SIZE)
    assert np.isclose(tracks[1].position[2], middle[2], atol=0.002)
    beside = top + np.array([0.06, 0.0, 0.0]) - 2 * up  # taken off and put on the table beside: it goes
    for _ in range(DOUBT_FRAMES + 2):
        tracks = tracker.update([seen(0, bottom), seen(1, middle), seen(2, beside)], hand)
    assert np.allclose(tracks[2].position, beside, atol=0.005)
