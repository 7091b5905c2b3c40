; Two blocks (paper, "Experiments"): predicates close, above, holding; sub-goal types pick, put near,
; put away, put on top. Each action is one sub-goal; its effects are the literals the sub-goal makes
; true (semgoal_core.vocabulary.SubGoal.literals) plus what follows physically (a block put on another
; is close to it). hand-empty is a planning helper derived from "no holding(x)"; close is kept symmetric.
(define (domain two_blocks)
  (:requirements :typing :negative-preconditions :equality)
  (:types block)
  (:predicates (close ?a - block ?b - block) (above ?a - block ?b - block) (holding ?a - block) (hand-empty))

  ; ?under: the other block (x is lifted off it if it was stacked); nothing may sit on ?x
  (:action pick
    :parameters (?x - block ?under - block)
    :precondition (and (hand-empty) (not (= ?x ?under)) (not (above ?under ?x)))
    :effect (and (holding ?x) (not (hand-empty)) (not (above ?x ?under))))

  (:action put_near
    :parameters (?x - block ?y - block)
    :precondition (and (holding ?x) (not (= ?x ?y)))
    :effect (and (close ?x ?y) (close ?y ?x) (hand-empty) (not (holding ?x))))

  (:action put_away
    :parameters (?x - block ?y - block)
    :precondition (and (holding ?x) (not (= ?x ?y)))
    :effect (and (not (close ?x ?y)) (not (close ?y ?x)) (hand-empty) (not (holding ?x))))

  (:action put_on
    :parameters (?x - block ?y - block)
    :precondition (and (holding ?x) (not (= ?x ?y)))
    :effect (and (above ?x ?y) (close ?x ?y) (close ?y ?x) (hand-empty) (not (holding ?x)))))
