; Three blocks (paper, "Experiments"): predicates close and holding; sub-goal types pick, put near,
; put away. Every put says where the moved block ends up with respect to both other blocks: near ?y and
; not near ?z (put_near), near both (put_near_both), away from both (put_away_both). A put that left
; close(?x ?z) to the frame would promise that a block carried across the table stays next to ?z, which
; the actor is never asked for. A block is put near two references only when they are close
; to each other (next to a pair, as the expert does). Put away comes first so that breadth-first search
; prefers it among plans of equal length.
(define (domain three_blocks)
  (:requirements :typing :negative-preconditions :equality)
  (:types block)
  (:predicates (close ?a - block ?b - block) (holding ?a - block) (hand-empty))

  (:action pick
    :parameters (?x - block)
    :precondition (hand-empty)
    :effect (and (holding ?x) (not (hand-empty))))

  (:action put_away_both
    :parameters (?x - block ?y - block ?z - block)
    :precondition (and (holding ?x) (not (= ?x ?y)) (not (= ?x ?z)) (not (= ?y ?z)))
    :effect (and (not (close ?x ?y)) (not (close ?y ?x)) (not (close ?x ?z)) (not (close ?z ?x))
                 (hand-empty) (not (holding ?x))))

  (:action put_near
    :parameters (?x - block ?y - block ?z - block)
    :precondition (and (holding ?x) (not (= ?x ?y)) (not (= ?x ?z)) (not (= ?y ?z)))
    :effect (and (close ?x ?y) (close ?y ?x) (not (close ?x ?z)) (not (close ?z ?x)) (hand-empty) (not (holding ?x))))

  (:action put_near_both
    :parameters (?x - block ?y - block ?z - block)
    :precondition (and (holding ?x) (close ?y ?z) (not (= ?x ?y)) (not (= ?x ?z)))
    :effect (and (close ?x ?y) (close ?y ?x) (close ?x ?z) (close ?z ?x) (hand-empty) (not (holding ?x)))))
