; Tabletop (beyond the paper): all four predicates on one table with a bin, towers of any height. Sub-goal
; types pick, put near, put away, put on (onto a block, the top of a tower of any height), put on the table and
; put in the bin. Each action is one sub-goal; its effects are the literals the sub-goal makes true plus what
; follows physically (a block put on another is close to it; a block picked up leaves the bin and the block it
; stood on). Helpers derived from the semantic state (semgoal_planner.semantic): hand-empty (no holding), clear
; (no block above it) and grounded (above no block: on the table or in the bin). Nothing is put on, or near, a
; block in the bin; a block is put near a lone block on the table (beside a block up a tower it would stand too
; far below to be close, and beside a tower's foot the hand brushed the tower over). Costs say which put a plan
; prefers where several do: on the table or in the bin 1, near or away 2, on a block 3. A tower comes down onto the
; table, where the expert finds room, with no closeness promised that nothing needs (put near a block at the table's
; edge found no spot), and a block asked to be near another is put beside it, not on it.
(define (domain tabletop)
  (:requirements :typing :negative-preconditions :equality :action-costs)
  (:types block)
  (:predicates (close ?a - block ?b - block) (above ?a - block ?b - block) (holding ?a - block)
               (in_bin ?a - block) (hand-empty) (clear ?a - block) (grounded ?a - block))
  (:functions (total-cost) - number)

  (:action pick
    :parameters (?x - block)
    :precondition (and (hand-empty) (clear ?x) (grounded ?x))
    :effect (and (increase (total-cost) 1) (holding ?x) (not (hand-empty)) (not (grounded ?x)) (not (in_bin ?x))))

  (:action pick_from
    :parameters (?x - block ?under - block)
    :precondition (and (hand-empty) (clear ?x) (above ?x ?under))
    :effect (and (increase (total-cost) 1) (holding ?x) (not (hand-empty)) (not (above ?x ?under)) (clear ?under)))

  (:action put_on
    :parameters (?x - block ?y - block)
    :precondition (and (holding ?x) (clear ?y) (not (in_bin ?y)) (not (= ?x ?y)))
    :effect (and (increase (total-cost) 3) (above ?x ?y) (close ?x ?y) (close ?y ?x) (not (clear ?y)) (hand-empty) (not (holding ?x))))

  (:action put_on_table
    :parameters (?x - block)
    :precondition (holding ?x)
    :effect (and (increase (total-cost) 1) (grounded ?x) (hand-empty) (not (holding ?x))))

  (:action put_near
    :parameters (?x - block ?y - block)
    :precondition (and (holding ?x) (grounded ?y) (clear ?y) (not (in_bin ?y)) (not (= ?x ?y)))
    :effect (and (increase (total-cost) 2) (close ?x ?y) (close ?y ?x) (grounded ?x) (hand-empty) (not (holding ?x))))

  (:action put_away
    :parameters (?x - block ?y - block)
    :precondition (and (holding ?x) (not (= ?x ?y)))
    :effect (and (increase (total-cost) 2) (not (close ?x ?y)) (not (close ?y ?x)) (grounded ?x) (hand-empty) (not (holding ?x))))

  (:action put_in_bin
    :parameters (?x - block)
    :precondition (holding ?x)
    :effect (and (increase (total-cost) 1) (in_bin ?x) (grounded ?x) (hand-empty) (not (holding ?x)))))
