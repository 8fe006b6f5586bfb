"""What a goal's answer can depend on (foon2asp/api/goal_parts.py): the motions and kitchen items
of its relevant part, and a knowledge base without some kitchen items."""

from __future__ import annotations

import pytest

import foon2asp
from foon2asp.api.goal_parts import relevant_part, without_kitchen_items


@pytest.fixture(scope="module")
def kb(shared_foon_dir):
    return foon2asp.load(shared_foon_dir)


def test_the_relevant_part_names_the_motions_and_kitchen_items_a_tree_can_use(kb):
    part = relevant_part(kb, "macaroni")
    assert part.goal.label == "macaroni" and part.units == 25
    assert part.motions == (
        "boil",
        "cook",
        "fill",
        "heat",
        "pick-and-place",
        "pour",
        "remove",
        "sprinkle",
        "stir and melt",
        "turn on",
    )
    tree = kb.solve("macaroni")
    p = kb.problem
    needed = {p.objects[o].text for u in tree.unit_ids for o in p.required[u] if o in p.kitchen}
    texts = {o.text for o in part.kitchen}
    assert {"water, in [pot]", "salt, granulated, in [shaker]"} <= needed <= texts
    assert "jar, contains {macaroni}" not in texts  # a utensil holding an input: not needed (the utensil rule)
    assert {u.motion for u in tree.units} <= set(part.motions)


def test_a_kitchen_without_an_item_answers_without_it(kb):
    bowl = "mixing bowl, empty"
    smaller = without_kitchen_items(kb, [bowl])
    assert kb.solve("greek salad").status == "optimal"  # the knowledge base itself is unchanged
    assert smaller.solve("greek salad").status == "unreachable"
    assert [o.text for o in smaller.missing("greek salad").missing] == [bowl]
    spoonless = without_kitchen_items(kb, ["spoon, empty"]).solve("greek salad")
    assert (spoonless.status, spoonless.cost["units"]) == ("optimal", 30)
    assert without_kitchen_items(kb, []) is kb


def test_only_a_kitchen_item_can_be_taken_out(kb):
    with pytest.raises(foon2asp.InputError, match="is not a kitchen item"):
        without_kitchen_items(kb, ["greek salad"])
    with pytest.raises(foon2asp.InputError, match="no goal or FOON object labelled 'no such thing'"):
        without_kitchen_items(kb, ["no such thing"])
