; Desk cleanup (paper, "Experiments"): predicates holding and in_bin; sub-goal types pick, put on
; table, put in bin. A block picked out of the bin is lifted out of it.
(define (domain desk_cleanup)
  (:requirements :typing :negative-preconditions)
  (:types block)
  (:predicates (holding ?a - block) (in_bin ?a - block) (hand-empty))

  (:action pick
    :parameters (?x - block)
    :precondition (hand-empty)
    :effect (and (holding ?x) (not (hand-empty)) (not (in_bin ?x))))

  (:action put_in_bin
    :parameters (?x - block)
    :precondition (holding ?x)
    :effect (and (in_bin ?x) (hand-empty) (not (holding ?x))))

  (:action put_on_table
    :parameters (?x - block)
    :precondition (holding ?x)
    :effect (and (not (in_bin ?x)) (hand-empty) (not (holding ?x)))))
