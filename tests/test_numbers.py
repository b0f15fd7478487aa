"""Spoken numbers and quantities, in SI: digits and words, fractions, compounds, units."""

from __future__ import annotations

import math

import pytest

from stuart_bt.language.numbers import ANGLE, LENGTH, digits_for_words, ordinal, read_number, read_quantity, word_value


def toks(text: str) -> list[str]:
    return text.split()


@pytest.mark.parametrize("text,value", [
    ("two", 2), ("seven", 7), ("twelve", 12), ("twenty", 20), ("forty five", 45), ("ninety", 90),
    ("one hundred", 100), ("a hundred", 100), ("one hundred and eighty", 180), ("a hundred and twenty", 120),
    ("one eighty", 180), ("two seventy", 270), ("three sixty", 360), ("one fifteen", 115),
    ("1", 1), ("1.5", 1.5), ("1,5", 1.5), ("0.25", 0.25), ("90", 90),
    ("half", 0.5), ("a half", 0.5), ("a quarter", 0.25), ("three quarters", 0.75), ("two thirds", 2 / 3),
    ("one and a half", 1.5), ("two and a half", 2.5), ("2 and a half", 2.5), ("one and three quarters", 1.75),
    ("one point five", 1.5), ("zero point seven five", 0.75), ("a couple of", 2), ("a couple", 2), ("a few", 3),
    ("point five", 0.5), ("point two five", 0.25), ("point 5", 0.5), ("one point 25", 1.25),
    ("nought point five", 0.5), ("several", 3),
])
def test_numbers(text: str, value: float) -> None:
    got = read_number(toks(text), 0)
    assert got is not None and got[0] == pytest.approx(value)
    assert got[1] == len(toks(text)), "the whole phrase is read"


@pytest.mark.parametrize("text", ["a", "the", "kitchen", "and", "point", "", "third"])
def test_not_numbers(text: str) -> None:
    assert read_number(toks(text), 0) is None


def test_reading_stops_where_the_number_ends() -> None:
    assert read_number(toks("two metres forward"), 0) == (2.0, 1)
    assert read_number(toks("forty five degrees left"), 0) == (45.0, 2)
    assert read_number(toks("one and then turn"), 0) == (1.0, 1)  # "and then" is no fraction
    assert read_number(toks("ninety ninety"), 0) == (90.0, 1)


@pytest.mark.parametrize("text,value,dim", [
    ("two metres", 2, LENGTH), ("2 m", 2, LENGTH), ("1.5 m", 1.5, LENGTH), ("a metre", 1, LENGTH),
    ("an inch", 0.0254, LENGTH), ("half a metre", 0.5, LENGTH), ("a half metre", 0.5, LENGTH),
    ("a quarter of a metre", 0.25, LENGTH), ("three quarters of a metre", 0.75, LENGTH),
    ("one and a half metres", 1.5, LENGTH), ("a metre and a half", 1.5, LENGTH), ("2 metres and a half", 2.5, LENGTH),
    ("50 cm", 0.5, LENGTH), ("fifty centimetres", 0.5, LENGTH), ("seventy five centimeters", 0.75, LENGTH),
    ("500 mm", 0.5, LENGTH), ("3 feet", 0.9144, LENGTH), ("a yard", 0.9144, LENGTH),
    ("a couple of metres", 2, LENGTH), ("a few metres", 3, LENGTH), ("one metre fifty", 1.5, LENGTH),
    ("a metre fifty", 1.5, LENGTH), ("a metre and 20 centimetres", 1.2, LENGTH),
    ("one metre and fifty centimetres", 1.5, LENGTH), ("a hundred and twenty centimetres", 1.2, LENGTH),
    ("two steps", 1.0, LENGTH), ("a step", 0.5, LENGTH), ("to meters", 2, LENGTH),
    ("ninety degrees", math.pi / 2, ANGLE), ("90 deg", math.pi / 2, ANGLE), ("45 °", math.pi / 4, ANGLE),
    ("one hundred and eighty degrees", math.pi, ANGLE), ("a quarter turn", math.pi / 2, ANGLE),
    ("half a turn", math.pi, ANGLE), ("a full turn", 2 * math.pi, ANGLE), ("one full turn", 2 * math.pi, ANGLE),
    ("1.57 radians", 1.57, ANGLE), ("two seventy degrees", 3 * math.pi / 2, ANGLE),
    ("90", 90, ""), ("forty five", 45, ""), ("two", 2, ""),
])
def test_quantities(text: str, value: float, dim: str) -> None:
    q = read_quantity(toks(text), 0)
    assert q is not None, text
    assert q.value == pytest.approx(value) and q.dimension == dim
    assert q.end == len(toks(text))


@pytest.mark.parametrize("text", ["a", "a cup", "the metre", "metres", "to the kitchen", "for the cup"])
def test_not_quantities(text: str) -> None:
    assert read_quantity(toks(text), 0) is None


def test_quantity_in_the_middle_of_a_sentence() -> None:
    t = toks("go forward two and a half metres then stop")
    q = read_quantity(t, 2)
    assert q is not None and q.value == 2.5 and t[q.end] == "then"


def test_word_value_and_ordinals() -> None:
    assert word_value("seven") == 7 and word_value("40") == 40 and word_value("kitchen") is None
    assert ordinal("third") == 3 and ordinal("3rd") == 3 and ordinal("21st") == 21 and ordinal("three") is None


def test_digits_for_words() -> None:
    assert digits_for_words(toks("station three")) == ["station", "3"]
    assert digits_for_words(toks("the third station")) == ["the", "3", "station"]
    assert digits_for_words(toks("a cup")) == ["a", "cup"]
