"""The command grammar: the text after the wake phrase -> an ordered list of TaskIntents.

Deterministic and rule-based on purpose: a robot must do the same thing for the same words, a
misheard command must fail visibly rather than be guessed, and a parse must cost microseconds
(the budget is 50 µs at p99, see bench/parse.py). Shape of the grammar::

    command   := clause (connector clause)*
    connector := "," | "and" | "then" | "and then" | "after that" | ";" | "." | "to" (+verb) | ...
    clause    := polite* verb-phrase trailing*  |  ellipsis
    polite    := "please" | "could you" | "would you mind" | "i want you to" | "let's" | ...
    ellipsis  := noun-phrase (same action as the clause before: "go to the kitchen and the bathroom")
               | direction/quantity ("turn left, then right"; "forward two metres")
               | gesture phrase ("high five!")

Each verb family has a small recursive-descent reader (motion, turn, pick, find, gesture,
stop, and the light verbs do/make/give/show/take that lead into the others). Readers consume
tokens from a position and return intents plus the position after them; anything they do not
understand ends the clause.

What is *not* a command: a sentence that opens like a question or a statement ("what can you
pick up?", "do you like the kitchen?", "I went to the kitchen", "the kitchen is nice") is
conversation to its end (the next "." "?" "!" or ";"), even if a command-like clause follows an
"and". Polite questions are commands ("could you go to the kitchen?", "can you wave?"), except
questions about wishes ("would you like to go to the kitchen?"). Negated commands ("don't go to
the kitchen") give nothing, except "don't move", which is a stop.

The grammar reports targets as spoken (lower case, determiners removed): "the charging dock"
-> "charging dock". Mapping them to marker names and object labels is
:mod:`stuart_bt.language.resolve`'s job, so parsing never needs a map.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable, Iterable
from dataclasses import dataclass

from .intents import FIND, GESTURE, MOVE, NAVIGATE, PICK, STOP, TURN, TURN_AROUND, TaskIntent
from .numbers import ANGLE, LENGTH, SOUNDS_LIKE, STEP_M, UNITS, read_number, read_quantity, word_value

Spec = tuple[str, str, float, float, float]  # (action, target, x, y, yaw): an intent without raw_text
Result = tuple[list[Spec], int] | None


@dataclass(frozen=True)
class Defaults:
    """Amounts used when the speaker gives none. Why these: a metre is the smallest distance
    the G1 walks cleanly (its controller ignores speeds below ~0.3 m/s, so shorter moves are
    mostly start and stop); a step of the G1 is about half a metre; "turn left" means a right
    angle; "a bit" is deliberately small."""

    move_m: float = 1.0
    vague_move_m: float = 0.5  # "a bit", "a little", "slightly"
    step_m: float = STEP_M  # "take a step back" (numbers.STEP_M: "two steps" is a length)
    turn_deg: float = 90.0
    vague_turn_deg: float = 30.0


# -- tokens ------------------------------------------------------------------------------------------
_NUM_UNIT = re.compile(r"(\d+(?:[.,]\d+)?)([^\W\d_]+|°)$")
MAX_TOKENS = 200  # a spoken command is never longer; the rest of a longer text is not read

DISFLUENCIES = frozenset({"um", "umm", "uh", "uhh", "uhm", "er", "erm", "ehm", "hmm", "hm", "mm", "mmm", "ah", "ahh"})
SPLITS: dict[str, tuple[str, ...]] = {
    "pickup": ("pick", "up"), "highfive": ("high", "five"), "uturn": ("u", "turn"), "xray": ("x", "ray"),
    "wanna": ("want", "to"), "gotta": ("got", "to"), "cannot": ("can", "not"), "nevermind": ("never", "mind"),
    "lookfor": ("look", "for"), "okay": ("ok",), "alright": ("ok",), "estop": ("e", "stop"),
    "anticlockwise": ("anticlockwise",), "counterclockwise": ("anticlockwise",),
    "metres": ("metres",),
    "gimme": ("give", "me"), "lemme": ("let", "me"), "gonna": ("going", "to"),
}

# -- lexicon -----------------------------------------------------------------------------------------
HARD_STOPS = frozenset({".", ";", "!", "?"})
COPULA = frozenset({"is", "are", "was", "were", "isnt", "arent", "wasnt", "werent", "means"})
SUBORDINATORS = frozenset({"when", "once", "after", "whenever", "if"})
CONDITIONS = frozenset({"until", "till", "unless", "if", "while", "whenever", "because", "since"})
BOUNDARY = frozenset({",", ".", ";", "!", "?", "&", "and", "then", "but", "plus", "or", "afterwards",
                      "afterward", "after", "before", "once", "when", "finally", "lastly", "followed"})
DETERMINERS = frozenset({"the", "a", "an", "your", "my", "our", "this", "that", "these", "those", "some",
                         "his", "her", "their", "its", "any", "yonder", "both", "either"})
PRONOUNS = frozenset({"it", "them", "that", "this", "those", "these", "one", "that one", "this one", "thing"})
OBJECT_PRONOUNS = frozenset({"me", "us", "him", "her", "them", "everyone", "everybody", "you", "yourself"})
GENERIC = frozenset({"things", "stuff", "objects", "object", "items", "item", "anything", "something", "everything",
                     "thing", "nothing", "whatever", "all", "stuff up", "things up"})
NP_BLOCK = frozenset({"sleep", "bed", "hell", "heaven", "pieces", "waste", "war", "work", "school", "church",
                      "break", "rest", "nap", "seat", "look", "photo", "picture", "photograph", "selfie", "shower",
                      "bath", "walk", "hand", "minute", "second", "moment", "sec", "chance", "call", "try", "guess",
                      "hint", "clue", "idea", "deep breath", "breath", "breather", "left", "right", "way",
                      "step", "steps", "turn", "turns", "care", "part", "place", "note", "notice", "time", "pace",
                      "lead", "lesson", "chill pill", "joke", "pill", "hike", "stroll", "spin"})
NP_STOP = BOUNDARY | frozenset({
    "to", "from", "on", "in", "at", "into", "onto", "inside", "near", "next", "by", "with", "for", "off", "of",
    "please", "now", "quickly", "quick", "slowly", "carefully", "immediately", "again", "too", "first", "thanks",
    "thank", "up", "down", "over", "there", "here", "behind", "under", "beside", "between", "below", "above", "around",
    "across", "along", "towards", "toward", "through", "until", "till", "unless", "if", "while", "so",
    "because", "as", "without", "asap", "ok", "gently", "instead", "also", "real", "fast", "safely",
    "straight", "right", "yourself", "which", "who", "where", "whose", "thats", "will", "would", "can",
    "could", "since", "when", "once", "like", "shall", "yeah", "alright", "okay",
    "later", "soon", "today", "tonight", "tomorrow", "afterwards", "sometime",  # when, not what
    "no", "sorry", "oops", "i",  # a correction or a new sentence follows ("go to the kitchen i said")
    "is", "are", "was", "were",  # a clause: "pick up whatever is on the table"
    "you",  # a new clause: "... the kitchen you need a map"
    "together", "alone",
})
NP_LEADERS = frozenset({"marker", "waypoint", "location", "position", "object", "item"})  # "go to marker kitchen"
RELATIVE = frozenset({"that", "which", "who", "where"})  # end a noun phrase, but not at its start
TRAILING = frozenset({"please", "now", "quickly", "slowly", "carefully", "immediately", "again", "too", "first",
                      "thanks", "thank", "you", "ok", "asap", "gently", "instead", "also", "fast", "safely",
                      "right", "away", "straight", "real", "quick", "for", "me", "us", "as", "well", "if", "can",
                      "could", "will", "would", "possible", "buddy", "mate", "pal", "robot", "friend", "then",
                      "at", "once", "yourself", "soon", "sir", "dude", "man", "there", "here", "over", "shall",
                      "we", "yeah", "alright", "later", "today", "tonight", "tomorrow", "sometime"})

WH = frozenset({"what", "whats", "where", "wheres", "who", "whos", "why", "whys", "how", "hows", "when", "whens",
                "which", "whose", "whom", "whatever", "wat"})
AUX = frozenset({"is", "are", "was", "were", "am", "does", "did", "has", "had", "isnt", "arent", "wasnt", "werent",
                 "didnt", "doesnt", "hasnt", "havent", "shall", "might", "must", "should", "shouldnt", "may"})
SUBJECTS = frozenset({"i", "im", "ive", "id", "ill", "we", "were", "weve", "wed", "well", "he", "hes", "she",
                      "shes", "it", "its", "they", "theyre", "theyve", "this", "that", "thats", "there",
                      "theres", "here", "heres", "the", "my", "our", "his", "her", "their", "these", "those",
                      "youre", "youve", "youd", "youll", "everyone", "everybody", "nobody", "someone",
                      "somebody", "people", "mine", "yours", "a", "an", "one", "not", "probably", "if",
                      "because", "although", "though", "unless", "said"})
# Interjections ("great job, now wave", "no, go to the kitchen") neither command nor open a
# statement: the clause after them is read as usual.
MODALS = frozenset({"can", "could", "would", "will", "wont", "wouldnt", "cant", "couldnt"})
# questions about wishes and plans are conversation even though they are polite in form
WISH_QUESTIONS: tuple[tuple[str, ...], ...] = (
    ("would", "you", "like"), ("do", "you", "want"), ("would", "you", "want"), ("do", "you", "like"),
    ("would", "you", "rather"), ("do", "you", "need"), ("do", "you", "know"), ("can", "you", "tell"),
    ("could", "you", "tell"), ("will", "you", "ever"), ("do", "you", "think"), ("can", "i"), ("could", "i"),
    ("should", "i"), ("may", "i"), ("shall", "i"), ("shall", "we"), ("can", "we"), ("could", "we"),
    ("did", "you"), ("have", "you"), ("do", "you", "remember"),
    ("you", "went"), ("you", "are"), ("you", "were"), ("you", "did"), ("you", "have"), ("you", "like"),
    ("you", "know"), ("you", "look"), ("you", "seem"), ("you", "said"),
)
_WISH_BY_FIRST: dict[str, tuple[tuple[str, ...], ...]] = {}
for _w in WISH_QUESTIONS:
    _WISH_BY_FIRST[_w[0]] = _WISH_BY_FIRST.get(_w[0], ()) + (_w,)
POLITE: tuple[tuple[str, ...], ...] = tuple(sorted({
    ("please",), ("kindly",), ("just",), ("possibly",), ("perhaps", "you", "could"),
    ("i", "was", "wondering", "if", "you", "could"), ("i", "wonder", "if", "you", "could"),
    ("i", "was", "wondering", "whether", "you", "could"), ("i", "was", "hoping", "you", "could"),
    ("i", "hope", "you", "can"), ("any", "chance", "you", "could"), ("is", "there", "any", "chance", "you", "could"),
    ("would", "you", "kindly"), ("be", "a", "dear", "and"), ("be", "a", "good", "robot", "and"),
    ("now",), ("ok",), ("so",), ("well",), ("yes",), ("yeah",), ("also",),
    ("hey",), ("quickly",), ("quick",), ("right", "now"), ("maybe",), ("perhaps",), ("actually",), ("oh",),
    ("go", "ahead", "and"), ("lets",), ("let", "us"), ("let", "me", "see", "you"),
    ("i", "want", "you", "to"), ("i", "need", "you", "to"), ("i", "would", "like", "you", "to"),
    ("id", "like", "you", "to"), ("i", "would", "love", "you", "to"), ("id", "love", "you", "to"),
    ("i", "would", "love", "it", "if", "you", "could"), ("id", "love", "it", "if", "you", "could"),
    ("id", "like", "for", "you", "to"), ("i", "ask", "you", "to"), ("im", "asking", "you", "to"),
    ("i", "think", "you", "should"), ("i", "want", "to", "see", "you"), ("i", "wanna", "see", "you"),
    ("i", "order", "you", "to"), ("i", "command", "you", "to"), ("i", "need", "you", "to", "please"),
    ("you", "need", "to"), ("you", "have", "to"), ("you", "should"), ("you", "must"), ("you", "can"),
    ("you", "may"), ("you", "could"), ("you", "got", "to"), ("you", "ought", "to"), ("you", "gotta"),
    ("would", "you", "mind"), ("do", "you", "mind"), ("would", "you", "be", "so", "kind", "as", "to"),
    ("could", "you", "be", "so", "kind", "as", "to"), ("be", "so", "kind", "as", "to"),
    ("would", "you", "be", "able", "to"), ("are", "you", "able", "to"), ("is", "it", "possible", "for", "you", "to"),
    ("would", "it", "be", "possible", "for", "you", "to"), ("would", "it", "be", "possible", "to"),
    ("can", "i", "ask", "you", "to"), ("could", "i", "ask", "you", "to"), ("may", "i", "ask", "you", "to"),
    ("can", "i", "get", "you", "to"), ("could", "i", "get", "you", "to"),
    ("why", "dont", "you"), ("why", "not"), ("how", "about", "you"), ("how", "about"), ("what", "about", "you"),
    ("try", "to"), ("try", "and"), ("remember", "to"), ("dont", "forget", "to"), ("do", "not", "forget", "to"),
    ("make", "sure", "to"), ("make", "sure", "you"), ("be", "sure", "to"), ("its", "time", "to"), ("time", "to"),
    ("do", "me", "a", "favour", "and"), ("do", "me", "a", "favor", "and"), ("if", "you", "could"),
    ("if", "you", "can"), ("if", "you", "would"), ("could", "you", "maybe"), ("can", "you", "maybe"),
    ("i", "would", "appreciate", "it", "if", "you", "could"), ("id", "appreciate", "it", "if", "you", "could"),
    ("keep",), ("continue", "to"), ("carry", "on"), ("start",), ("start", "to"), ("begin", "to"), ("begin",),
    ("what", "i", "need", "is", "for", "you", "to"), ("what", "i", "want", "is", "for", "you", "to"),
    ("what", "id", "like", "is", "for", "you", "to"), ("what", "i", "would", "like", "is", "for", "you", "to"),
    ("all", "i", "need", "is", "for", "you", "to"), ("all", "i", "want", "is", "for", "you", "to"),
    ("what", "i", "need", "you", "to", "do", "is"), ("what", "i", "want", "you", "to", "do", "is"),
    ("what", "id", "like", "you", "to", "do", "is"), ("all", "you", "need", "to", "do", "is"),
    ("see", "if", "you", "can"), ("see", "if", "you", "could"), ("check", "if", "you", "can"),
    ("like",), ("now", "then"), ("alright", "then"), ("ok", "then"), ("good",), ("great",), ("thanks",),
    ("thank", "you"), ("cool",), ("sure",), ("fine",), ("right",), ("and", "now"), ("next",),
    ("instead",), ("instead", "of", "that"), ("rather",), ("off", "you"), ("help", "me"), ("help", "us"),
    ("please", "to"), ("mind",), ("you", "mind"),
}, key=lambda p: (-len(p), p)))
_POLITE_BY_FIRST: dict[str, tuple[tuple[str, ...], ...]] = {}
for _p in POLITE:
    _POLITE_BY_FIRST[_p[0]] = _POLITE_BY_FIRST.get(_p[0], ()) + (_p,)

CONNECTORS: tuple[tuple[str, ...], ...] = tuple(sorted({
    (",",), ("&",), ("and",), ("then",), ("plus",), ("and", "then"), ("and", "after", "that"), ("and", "afterwards"),
    ("and", "finally"), ("and", "also"), ("and", "next"), ("and", "lastly"), ("after", "that"), ("after", "this"),
    ("after", "which"), ("afterwards",), ("afterward",), ("finally",), ("lastly",), ("first",), ("firstly",),
    ("first", "of", "all"), ("secondly",), ("thirdly",), ("next",), ("then", "after", "that"), ("once", "done"),
    ("when", "done"), ("once", "there"), ("when", "there"), ("once", "you", "are", "there"),
    ("once", "youre", "there"), ("when", "you", "get", "there"), ("when", "you", "are", "there"),
    ("when", "youre", "there"),
    ("once", "you", "get", "there"), ("when", "youre", "done"), ("once", "youre", "done"),
    ("when", "you", "are", "done"), ("once", "youve", "done", "that"), ("when", "youve", "done", "that"),
    ("once", "thats", "done"), ("when", "thats", "done"), ("followed", "by"), ("and", "followed", "by"),
    ("as", "soon", "as", "you", "get", "there"), ("and", "when", "you", "get", "there"), ("and", "once", "there"),
    ("after", "you", "do", "that"), ("after", "doing", "that"), ("and", "after", "this"),
    ("then", "after", "this"), ("and", "then", "after", "that"), ("but",), ("and", "then", "finally"),
    ("in", "order", "to"), ("so", "that", "you", "can"), ("and", "right", "after", "that"),
    ("right", "after", "that"), ("immediately", "after", "that"), ("and", "immediately"),
    ("after", "that", "then"), ("and", "last"), ("last",), ("second",), ("third",), ("also",), ("and", "also"),
}, key=lambda c: (-len(c), c)))
REORDER = {("but", "first"), ("but", "before", "that"), ("before", "that"), ("but", "before", "you", "do", "that")}
_CONNECTORS_BY_FIRST: dict[str, tuple[tuple[str, ...], ...]] = {}
for _c in sorted(set(CONNECTORS) | REORDER, key=lambda c: (-len(c), c)):
    _CONNECTORS_BY_FIRST[_c[0]] = _CONNECTORS_BY_FIRST.get(_c[0], ()) + (_c,)

# directions: (dx, dy) for moves; LEFT/RIGHT also give the sign of a turn
FORWARD, BACKWARD, LEFT, RIGHT = (1, 0), (-1, 0), (0, 1), (0, -1)
DIRECTIONS: dict[str, tuple[int, int]] = {
    **dict.fromkeys(("forward", "forwards", "ahead", "onward", "onwards", "front", "foreward", "fwd", "forth",
                     "frontward", "frontwards"), FORWARD),
    **dict.fromkeys(("back", "backward", "backwards", "backwords", "reverse", "backward's", "rearward",
                     "rearwards", "behind"), BACKWARD),
    **dict.fromkeys(("left", "leftward", "leftwards", "lefthand"), LEFT),
    **dict.fromkeys(("right", "rightward", "rightwards", "righthand"), RIGHT),
}
ROTATIONS: dict[str, int] = {"clockwise": -1, "anticlockwise": 1, "counterclockwise": 1, "cw": -1, "ccw": 1,
                             "left": 1, "right": -1, "leftward": 1, "rightward": -1, "leftwards": 1,
                             "rightwards": -1, "port": 1, "starboard": -1,
                             "rite": -1, "write": -1, "wright": -1}  # a recogniser's "right", after a turn verb only
VAGUE = frozenset({("a", "bit"), ("a", "little"), ("a", "little", "bit"), ("slightly",), ("a", "tad"),
                   ("a", "touch"), ("a", "tiny", "bit"), ("just", "a", "bit"), ("just", "a", "little"),
                   ("little", "bit"), ("bit",), ("a", "smidge"), ("somewhat",), ("a", "few", "degrees"),
                   ("a", "few", "centimetres"), ("a", "little", "way"), ("a", "few", "centimeters")})
_VAGUE_BY_FIRST: dict[str, tuple[tuple[str, ...], ...]] = {}
for _v in sorted(VAGUE, key=lambda v: (-len(v), v)):
    _VAGUE_BY_FIRST[_v[0]] = _VAGUE_BY_FIRST.get(_v[0], ()) + (_v,)
MOVE_FILLER = frozenset({"by", "for", "about", "roughly", "approximately", "exactly", "some", "another", "only",
                         "precisely", "the", "to", "your", "my", "its", "approx", "around", "just", "like",
                         "maybe", "over", "sideways", "straight", "directly", "further", "farther", "more",
                         "again", "on", "towards", "toward", "way", "in"})
TURN_FILLER = frozenset({"by", "to", "the", "your", "my", "through", "about", "roughly", "approximately",
                         "exactly", "another", "towards", "toward", "on", "yourself", "body", "self", "in",
                         "place", "direction", "side", "spot", "way", "just", "precisely", "over", "for", "some",
                         "like", "its", "a", "an", "of", "all"})
AROUND = frozenset({"around", "round", "about", "aroud", "arround"})
TO_WORDS = frozenset({"to", "towards", "toward", "into", "unto", "til", "till", "onto", "inside", "for"})
HOME = frozenset({"home", "base"})
CHOICES = frozenset({"number", "card", "one", "side", "colour", "color", "winner", "fight", "fights", "battle",
                     "battles", "lock", "team", "name",
                     "song", "movie", "film", "game", "date", "time", "option", "answer", "favourite", "favorite",
                     "quarrel", "nose", "brain", "brains", "spot", "moment", "word", "letter", "something"})
# what an object is taken "from" that is furniture, not a place to go ("the cup from the table")
SURFACES = frozenset({"table", "counter", "shelf", "desk", "floor", "ground", "chair", "box", "bag", "drawer",
                      "fridge", "cupboard", "cabinet", "sink", "tray", "rack", "bin", "basket", "bed", "sofa",
                      "couch", "stand", "top", "hand", "hands", "pile", "stack", "windowsill", "sill", "ledge",
                      "bookshelf", "bookcase", "cart", "trolley", "container", "crate", "pocket", "holder",
                      "countertop", "tabletop", "surface", "pedestal", "stool", "mat", "rug", "carpet"})

# gesture phrases -> the gesture library's canonical name (stuart_bt.core.gestures), except that every
# waving request is "wave" (the library plays it as "high wave"): the name people say.
_GESTURE_FORMS: dict[str, tuple[str, ...]] = {
    "high five": ("high five", "hi five", "high 5", "hi 5", "high fives", "five", "hi fives"),
    "wave": ("wave", "high wave", "hand wave", "big wave", "little wave", "friendly wave", "waves", "wave hello",
             "wave goodbye", "goodbye wave", "hello wave", "wave gesture"),
    "face wave": ("face wave",),
    "clap": ("clap", "claps", "applause", "round of applause", "hand clap", "clapping", "applaud", "big clap"),
    "hug": ("hug", "hugs", "big hug", "cuddle", "embrace", "bear hug", "little hug"),
    "heart": ("heart", "heart sign", "heart shape", "love heart", "heart gesture", "two hand heart",
              "heart with your hands", "big heart", "hand heart", "love sign"),
    "right heart": ("right heart", "right hand heart", "heart with your right hand", "one hand heart"),
    "shake hand": ("handshake", "hand shake", "shake hand", "shake hands", "shake of the hand", "hand shaking"),
    "hands up": ("hands up", "arms up", "both hands up", "both arms up", "hands in the air", "arms in the air",
                 "hands up high"),
    "right hand up": ("right hand up", "right arm up", "hand up", "arm up"),
    "two hand kiss": ("kiss", "two hand kiss", "two handed kiss", "air kiss", "flying kiss", "kisses",
                      "blown kiss"),
    "left kiss": ("left kiss", "left hand kiss", "kiss with your left hand"),
    "right kiss": ("right kiss", "right hand kiss", "kiss with your right hand"),
    "x-ray": ("x ray", "x rays", "xray pose", "x ray pose", "x pose", "x ray gesture"),
    "reject": ("reject", "rejection", "reject gesture", "no gesture", "refusal"),
    "release arm": ("release arm", "arms down", "hands down", "release arms", "arm down"),
}
GESTURE_PHRASES: dict[tuple[str, ...], str] = {tuple(f.split()): name for name, forms in _GESTURE_FORMS.items()
                                               for f in forms}
_GESTURE_BY_FIRST: dict[str, tuple[tuple[str, ...], ...]] = {}
for _g in sorted(GESTURE_PHRASES, key=lambda g: (-len(g), g)):
    _GESTURE_BY_FIRST[_g[0]] = _GESTURE_BY_FIRST.get(_g[0], ()) + (_g,)
GESTURE_NOUNS = frozenset({"gesture", "pose", "sign", "move", "motion", "emote", "animation", "action", "thing",
                           "please", "now", "for", "me", "us", "again"})
BODY = frozenset({"hand", "hands", "arm", "arms"})

# -- the verb lexicon: every base form the grammar knows, by family ---------------------------------
MOTION_VERBS = frozenset({"go", "move", "walk", "head", "drive", "travel", "proceed", "navigate", "come", "run",
                          "jog", "hurry", "rush", "return", "advance", "roll", "scoot", "shift", "slide", "strafe",
                          "sidestep", "wander", "stroll", "march", "visit", "approach", "reach", "enter", "step",
                          "back", "get", "retreat", "creep", "shuffle", "inch", "hop", "make", "scurry", "dash",
                          "sprint", "zoom", "trot", "amble", "journey", "relocate", "continue", "goto", "gp", "nudge",
                          "edge",
                          "budge", "crawl", "glide", "push", "ease", "wheel", "pop", "nip"})
TURN_VERBS = frozenset({"turn", "rotate", "spin", "pivot", "swivel", "twist", "face", "revolve", "veer", "swing"})
PICK_VERBS = frozenset({"pick", "grab", "grasp", "take", "fetch", "collect", "lift", "retrieve", "bring",
                        "carry", "get", "hand", "pass", "give", "snatch", "obtain", "gather", "seize", "acquire",
                        "deliver", "pluck", "procure", "nab", "raise"})
FIND_VERBS = frozenset({"find", "locate", "spot", "seek", "detect", "search", "look", "hunt", "scan", "track",
                        "check"})
# a find verb said as a noun after a light verb: "have a look for", "take a quick look around for"
FIND_NOUNS = frozenset({"look", "search", "hunt", "scan", "check", "peek", "peep", "glance"})
FIND_NOUN_LEADS = frozenset({"have", "take", "do", "give", "make"})
STOP_VERBS = frozenset({"stop", "halt", "freeze", "pause", "cancel", "abort", "wait", "stay", "quit", "cease",
                        "stand", "hold", "whoa", "woah", "enough", "never", "forget", "cut", "terminate", "end",
                        "interrupt", "chill", "hang", "desist", "emergency", "e", "brake", "kill", "break", "wo"})
GESTURE_VERBS = frozenset({"wave", "clap", "applaud", "hug", "cuddle", "embrace", "shake", "kiss", "blow", "say",
                           "greet", "raise", "put", "lower", "drop", "relax", "release", "rest", "reject"})
GUIDE_VERBS = frozenset({"lead", "guide", "escort", "accompany", "usher", "follow"})
LIGHT_VERBS = frozenset({"do", "make", "perform", "give", "show", "take", "throw", "try", "play"})
ALL_VERBS = (MOTION_VERBS | TURN_VERBS | PICK_VERBS | FIND_VERBS | STOP_VERBS | GESTURE_VERBS | LIGHT_VERBS
             | GUIDE_VERBS)
# verbs that start a new command even with no connector before them ("go to the kitchen turn left")
STRONG_VERBS = frozenset({"go", "turn", "move", "walk", "head", "pick", "grab", "find", "stop", "rotate",
                          "navigate", "wave", "clap", "come", "return", "locate", "fetch", "drive", "spin",
                          "halt", "freeze", "search", "bring"})


# a verb followed by one of its particles starts a new command inside a noun phrase ("... the
# kitchen look for the apple"); as a pair these are not read as nouns ("look" alone may be)
VERB_PARTICLES = frozenset({
    ("look", "for"), ("search", "for"), ("hunt", "for"), ("check", "for"), ("pick", "up"), ("back", "up"),
    ("step", "back"),
    ("step", "forward"), ("hold", "on"), ("hang", "on"), ("wait", "there"), ("wait", "for"), ("stay", "there"),
    ("take", "a"), ("turn", "around"), ("spin", "around"), ("face", "the"), ("shake", "hands"),
    ("give", "me"), ("hand", "me"), ("bring", "me"), ("get", "me"), ("fetch", "me"), ("grab", "me"),
    ("move", "forward"), ("move", "back"), ("come", "back"), ("head", "back"), ("head", "to"), ("head", "over"),
})


def _gerunds(verbs: Iterable[str]) -> dict[str, str]:
    """ing-forms of the known verbs ("turning" -> "turn", "stopping" -> "stop", "waving" ->
    "wave"): "would you mind turning left" and "stop moving" read like the plain verb."""
    out: dict[str, str] = {}
    for v in verbs:
        if len(v) < 2:
            continue
        out[v + "ing"] = v
        if v.endswith("e") and not v.endswith("ee"):
            out[v[:-1] + "ing"] = v
        out[v + v[-1] + "ing"] = v
    return out


GERUNDS = _gerunds(ALL_VERBS)


def _past(verbs: Iterable[str]) -> dict[str, str]:
    """Past forms of the known verbs ("picked" -> "pick", "grabbed" -> "grab", "found" ->
    "find"), read as the verb only in a perfect subordinate clause ("when/once/after you've",
    "... you have") or after "once you": "once you've picked up the bottle, head to the dock".
    Elsewhere a past verb tells a story ("when you went to the kitchen, was it clean?")."""
    out: dict[str, str] = {}
    for v in verbs:
        if len(v) < 2:
            continue
        out[v + "d" if v.endswith("e") else v + "ed"] = v
        out[v + v[-1] + "ed"] = v
        if v.endswith("y"):
            out[v[:-1] + "ied"] = v
    out.update({"went": "go", "gone": "go", "found": "find", "got": "get", "gotten": "get", "took": "take",
                "taken": "take", "brought": "bring", "came": "come", "ran": "run", "held": "hold", "stood": "stand",
                "gave": "give", "given": "give", "made": "make", "spun": "spin", "shook": "shake", "sought": "seek",
                "stopped": "stop", "caught": "catch"})
    return out


PAST = _past(ALL_VERBS)
_SPECIAL = frozenset(DISFLUENCIES | set(SPLITS) | set(GERUNDS))


class Tokens:
    """The tokens of a text and, computed only when asked (for ``raw_text``), their spans."""

    __slots__ = ("_low", "_offsets", "_raw", "_src", "toks")

    def __init__(self, toks: list[str], src: list[int], raw: list[str], low: str) -> None:
        self.toks = toks
        self._src = src  # token index -> index of the whitespace-separated piece it came from
        self._raw = raw
        self._low = low
        self._offsets: list[int] | None = None

    def without(self, token: str) -> Tokens:
        """The same tokens with every ``token`` left out."""
        keep = [k for k, t in enumerate(self.toks) if t != token]
        return Tokens([self.toks[k] for k in keep], [self._src[k] for k in keep], self._raw, self._low)

    def span(self, first: int, last: int) -> tuple[int, int]:
        """Character span in the text from token ``first`` to token ``last`` (inclusive)."""
        if self._offsets is None:
            offsets, pos, low = [], 0, self._low
            for piece in self._raw:
                at = low.find(piece, pos)
                offsets.append(at)
                pos = at + len(piece)
            self._offsets = offsets
        a, b = self._src[first], self._src[last]
        return self._offsets[a], self._offsets[b] + len(self._raw[b])


_SEPARATE = str.maketrans({
    **{c: " " for c in "\"()[]{}<>*+=/|~^`@#$%:_-–—‐‑“”„«»…•·\t\n\r"},
    **{c: f" {c} " for c in ".,;!?&°"},
    "’": "'", "‘": "'",
})
_DECIMAL = re.compile(r"\d[.,]\d")
_NUMBER_PIECE = re.compile(r"\d+(?:[.,]\d+)?[^\W_]*|[^\W\d_][^\W_]*(?:'[^\W_]+)*|[.;!?,°&]")


def tokenize(text: str) -> Tokens:
    """Lower-case tokens of ``text``. Punctuation that separates clauses (``. , ; ! ? &``) is a
    token, other symbols are spaces; apostrophes are dropped ("let's" -> "lets": recognisers write
    both); number-unit runs are split ("1.5m"); hesitations ("um", "uh"; "mm" unless a number is
    before it: "500 mm") and immediate repeats ("the the") are removed; ing-forms of known verbs
    become the verb ("turning" -> "turn"). At most MAX_TOKENS tokens are read."""
    low = text.lower()
    if len(low) != len(text):  # a few characters change length in lower(): keep offsets right
        low = "".join(c.lower() if len(c.lower()) == 1 else c for c in text)
    if _DECIMAL.search(low):  # "1.5": the period is no separator here (rare: the slow way)
        pieces = _NUMBER_PIECE.findall(low.replace("’", "'").translate(_KEEP_POINTS))
    else:
        pieces = low.translate(_SEPARATE).split()
    toks: list[str] = []
    src: list[int] = []
    last = ""
    special = _SPECIAL
    for k, t in enumerate(pieces):
        if t in special or t == last or "'" in t or t[0] <= "9":
            if "'" in t:
                t = t.replace("'", "")
                if not t:
                    continue
            if t in DISFLUENCIES and not (t in UNITS and last and word_value(last) is not None):
                continue  # "um"; but "500 mm" is a unit, not a hum
            if t == last and t not in HARD_STOPS and t != ",":
                continue
            c = t[0]
            if "0" <= c <= "9":
                um = _NUM_UNIT.match(t)
                if um and um.group(2) in UNITS:
                    toks += (um.group(1), um.group(2))
                    src += (k, k)
                    last = um.group(2)
                    continue
            elif t in SPLITS:
                parts = SPLITS[t]
                toks += parts
                src += (k,) * len(parts)
                last = parts[-1]
                continue
            elif t in GERUNDS:
                t = GERUNDS[t]
        toks.append(t)
        src.append(k)
        last = t
        if len(toks) >= MAX_TOKENS:
            break
    return Tokens(toks, src, pieces, low)


_KEEP_POINTS = str.maketrans({c: " " for c in "\"()[]{}<>*+=/|~^`@#$%:_-–—‐‑“”„«»…•·\t\n\r"})


# -- parse state -------------------------------------------------------------------------------------
@dataclass
class _State:
    """One parse: the tokens, what came before (for "it", "there" and ellipsis) and settings."""

    toks: list[str]
    n: int
    defaults: Defaults
    stop_words: frozenset[str]
    last_action: str = ""
    last_object: str = ""
    last_place: str = ""
    topic: str = ""  # a bare noun phrase said before the command ("the kitchen, go there")
    first: bool = True
    subordinate: bool = False  # reading "when you ...": "you" is the subject, so no ellipsis

    def at(self, i: int) -> str:
        return self.toks[i] if i < self.n else ""

    def phrase_at(self, i: int, table: dict[str, tuple[tuple[str, ...], ...]]) -> tuple[str, ...] | None:
        """The longest entry of ``table`` (by first word) that the tokens at ``i`` spell."""
        forms = table.get(self.toks[i]) if i < self.n else None
        if forms:
            toks = self.toks
            for f in forms:
                k = len(f)
                if k == 1 or tuple(toks[i:i + k]) == f:
                    return f
        return None


def _done(s: _State, j: int) -> bool:
    """Whether the clause may end at ``j``: end of text, a connector, or trailing words only."""
    toks, n = s.toks, s.n
    while j < n:
        t = toks[j]
        if t in BOUNDARY:
            return True
        if t not in TRAILING and t not in s.stop_words:
            return False
        j += 1
    return True


# -- noun phrases ------------------------------------------------------------------------------------
def _np(s: _State, i: int) -> tuple[list[str], int]:
    """A noun phrase from ``i`` to the next connector, preposition or trailing word; leading
    determiners removed ("the red cup" -> ["red", "cup"]). Returns (words, end)."""
    toks, n, stop = s.toks, s.n, s.stop_words
    j = i
    while j < n:
        t = toks[j]
        if t in stop:
            if j == i and t in ("that", "this", "there", "here", "right"):
                j += 1  # "pick that up", "go there": the caller reads a pronoun
                if t != "that" or j >= n or toks[j] in stop:
                    break
                continue
            if t == "next" and j + 1 < n and toks[j + 1] not in ("to",):
                j += 1  # "the next station"
                continue
            if t == "right" and j > i and (j + 1 >= n or toks[j + 1] in BOUNDARY or toks[j + 1] in NP_STOP):
                break
            if t == "right" and j + 1 < n and toks[j + 1] not in ("now", "there", "here", "away"):
                j += 1  # "the right cup", "right kiss" read by other rules first
                continue
            break
        if j > i and t in STRONG_VERBS:
            break
        if j > i and t in ALL_VERBS and j + 1 < n and (t, toks[j + 1]) in VERB_PARTICLES:
            break
        if t == "back" and j > i and toks[j - 1] not in DETERMINERS and (
                j + 1 >= n or toks[j + 1] in TO_WORDS or toks[j + 1] in BOUNDARY or toks[j + 1] in HOME
                or toks[j + 1] in ("here", "there", "over")):
            break  # "bring the book back to the entrance", "put it back"
        j += 1
    words = toks[i:j]
    while len(words) > 1 and (words[0] in DETERMINERS or words[0] in NP_LEADERS):
        words = words[1:]
    return words, j


def _no_noun(words: list[str]) -> bool:
    """A cut-off phrase with no noun: a lone determiner ("go to the"), or a verb and its
    indirect object ("give me give me")."""
    return (len(words) == 1 and words[0] in DETERMINERS) or (
        len(words) == 2 and words[0] in ALL_VERBS and words[1] in OBJECT_PRONOUNS)


def _object(s: _State, words: list[str]) -> str | None:
    """The spoken object of a pick or find, with "it"/"them"/"that one" meaning the last object
    named in this command; ``None`` when nothing usable was said."""
    if not words:
        return None
    text = " ".join(words)
    if text in PRONOUNS:
        return s.last_object or s.topic or None  # "pick it up" with nothing named before: no command
    if words[0] in ("it", "them", "him", "her", "me", "us") or _no_noun(words):
        return None  # "take it easy", "bring it on"
    if text in GENERIC or text in NP_BLOCK or text in OBJECT_PRONOUNS or words[0] in ("not", "no"):
        return None
    if all(word_value(w) is not None for w in words):
        return None  # "take five": a number is no object
    return text


def _place(s: _State, words: list[str]) -> str | None:
    """The spoken place of a navigation, with "there" meaning the last place named; a plural
    before a number is singular ("stations one, two and three": "station one", ...)."""
    if not words:
        return None
    if len(words) >= 2 and words[-2].endswith("s") and not words[-2].endswith("ss") and word_value(
            words[-1]) is not None:
        words = [*words[:-2], words[-2][:-1], words[-1]]
    text = " ".join(words)
    if text in ("there", "that place", "it", "that"):
        return s.last_place or s.topic or None
    if (text in GENERIC or text in NP_BLOCK or text in OBJECT_PRONOUNS or words[0] in ("not", "no") or text == "here"
            or _no_noun(words) or words[-1] in OBJECT_PRONOUNS):
        return None  # ... and "(sorry) to bother you": a verb and its object, no place
    return text


def _numbered(place: str) -> tuple[str, float] | None:
    """ "station three" -> ("station", 3.0): a place named by a number, or ``None``."""
    head, _, last = place.rpartition(" ")
    value = word_value(last) if head else None
    return (head, value) if value is not None else None


def _go(s: _State, target: str | None, e: int) -> Result:
    """navigate_to_marker ``target`` (ending at ``e``); a numbered range is one per number:
    "visit stations 1 to 3", "station one through three" -> station 1, station 2, station 3."""
    if target is None:
        return None
    num = _numbered(target) if s.at(e) in ("to", "through", "thru") else None
    last = word_value(s.at(e + 1)) if num else None
    if num and last is not None and num[1] == int(num[1]) and last == int(last) and num[1] < last <= num[1] + 10:
        return [(NAVIGATE, f"{num[0]} {k}", 0.0, 0.0, 0.0) for k in range(int(num[1]), int(last) + 1)], e + 2
    return [(NAVIGATE, target, 0.0, 0.0, 0.0)], e


# -- movement and turning ----------------------------------------------------------------------------
def _motion_terms(s: _State, i: int) -> tuple[tuple[int, int] | None, float | None, str, bool, int]:
    """Direction and amount after a motion or turn verb, in any order ("forward two metres",
    "2 m to the left", "a little to the right", "90 degrees clockwise"): (direction, amount,
    its dimension, vague?, end). A rotation word (clockwise) counts as LEFT/RIGHT."""
    toks, n = s.toks, s.n
    direction: tuple[int, int] | None = None
    amount: float | None = None
    dim = ""
    vague = False
    j = i
    for _ in range(12):
        if j >= n:
            break
        t = toks[j]
        if t in DIRECTIONS:
            d = DIRECTIONS[t]
            if direction is not None and d != direction:
                break  # "forward and left" is two moves; "forward left" is not understood
            direction = d
            j += 1
            continue
        if t in ("clockwise", "cw", "anticlockwise", "counterclockwise", "ccw"):
            direction = LEFT if ROTATIONS[t] > 0 else RIGHT
            j += 1
            continue
        if t in ("anti", "counter") and j + 1 < n and toks[j + 1] == "clockwise":
            direction = LEFT
            j += 2
            continue
        if amount is None:
            v = s.phrase_at(j, _VAGUE_BY_FIRST)
            if v is not None:
                vague = True
                j += len(v)
                continue
            if t in ("a", "an") and j + 1 < n and toks[j + 1] in ("few", "couple", "full", "quarter", "half"):
                pass
            q = read_quantity(toks, j) if (t[0].isdigit() or t in _NUMBER_STARTS or (
                t in SOUNDS_LIKE and j + 1 < n and toks[j + 1] in UNITS)) else None
            if q is not None:
                amount, dim = q.value, q.dimension
                j = q.end
                continue
        if t in MOVE_FILLER or t in TURN_FILLER:
            if t in ("the", "to", "your", "my") and j + 1 < n and (toks[j + 1] in DIRECTIONS or toks[j + 1] in (
                    "the", "your", "my", "left", "right") or toks[j + 1] in ROTATIONS):
                j += 1
                continue
            if t in ("a", "an", "the", "your", "my", "its", "of", "some", "way", "place", "side", "spot",
                     "direction") or (j + 1 < n and toks[j + 1] not in BOUNDARY):
                if t in ("a", "an") and not (j + 1 < n and (toks[j + 1] in UNITS or toks[j + 1] in _NUMBER_STARTS)):
                    break
                j += 1
                continue
        break
    return direction, amount, dim, vague, j


_NUMBER_STARTS = frozenset({
    "a", "an", "one", "two", "three", "four", "five", "six", "seven", "eight", "nine", "ten", "eleven", "twelve",
    "thirteen", "fourteen", "fifteen", "sixteen", "seventeen", "eighteen", "nineteen", "twenty", "thirty",
    "forty", "fourty", "fifty", "sixty", "seventy", "eighty", "ninety", "hundred", "half", "quarter", "quarters",
    "couple", "few", "several", "zero", "nought", "full", "complete", "whole", "pair", "pi", "point",
})


MAX_BARE_SIDESTEP_M = 10.0  # "left 90" with no unit: more than the lab is wide, so an angle
STEP_WORDS = frozenset(w for w, (dim, factor) in UNITS.items() if dim == LENGTH and factor == STEP_M)
_FRACTION_STARTS = frozenset({"a", "an", "half", "quarter", "quarters", "one", "three", "two"})  # "three quarters"


def _move(s: _State, i: int, verb: str, default_back: bool = False) -> Result:
    """move_relative from the direction/amount after a motion verb; ``None`` if neither was said
    or the amount is an angle."""
    direction, amount, dim, vague, j = _motion_terms(s, i)
    if direction is None and amount is None and not vague and not default_back:
        return None
    if dim == ANGLE:
        return None
    d = s.defaults
    if amount is None:
        amount = d.vague_move_m if vague else (d.step_m if verb in ("step", "sidestep") else d.move_m)
    elif dim == "" and verb in ("step", "sidestep"):
        amount *= d.step_m  # "step back two": two steps
    if direction is None:
        direction = BACKWARD if default_back else FORWARD
    return [(MOVE, "", amount * direction[0], amount * direction[1], 0.0)], j


def _turn_terms(s: _State, i: int, verb: str) -> Result:
    """turn_by_angle / turn_around from what follows a turn verb (or stands alone: "left 90")."""
    toks, n = s.toks, s.n
    j = i
    around = False
    sign = 0
    angle: float | None = None
    vague = False
    times = 1
    for _ in range(12):
        if j >= n:
            break
        t = toks[j]
        if t in AROUND or t in ("back", "backward", "backwards", "behind") and verb in ("turn", "face", "spin"):
            around = True
            j += 1
        elif t == "other" and j + 1 < n and toks[j + 1] in ("way", "direction", "side"):
            around = True
            j += 2
        elif t == "face" and verb != "face":  # "turn to face the other way"
            verb = "face"
            j += 1
        elif t == "away" and verb == "face":
            around = True
            j += 1
        elif t in ROTATIONS and sign == 0:
            sign = ROTATIONS[t]
            j += 1
        elif t in ("anti", "counter") and j + 1 < n and toks[j + 1] == "clockwise":
            sign = 1
            j += 2
        elif t == "twice":
            times = 2
            j += 1
        elif t in ("three", "four", "3", "4", "two", "2") and j + 1 < n and toks[j + 1] == "times":
            times = int(read_number(toks, j)[0])  # type: ignore[index]
            j += 2
        elif angle is None and not vague and s.phrase_at(j, _VAGUE_BY_FIRST) is not None:
            vague = True
            j += len(s.phrase_at(j, _VAGUE_BY_FIRST) or ())
        elif angle is None and (t[0].isdigit() or t in _NUMBER_STARTS or (
                t in SOUNDS_LIKE and j + 1 < n and toks[j + 1] in UNITS)) and (q := read_quantity(toks, j)) is not None:
            if q.dimension == LENGTH:
                return None
            if q.dimension == ANGLE:
                angle = q.value
            elif q.value < 1 and toks[j] in _FRACTION_STARTS:
                angle = q.value * 2 * math.pi  # "turn a quarter to the right", "turn half way round"
                if angle == math.pi and s.at(q.end) in ("way", "turn") and s.at(q.end + 1) in AROUND:
                    return [(TURN_AROUND, "", 0.0, 0.0, math.pi)], q.end + 2  # "half way round": around
            else:
                angle = math.radians(q.value)  # a bare number in a turn is degrees
            j = q.end
        elif t in TURN_FILLER and j + 1 < n and toks[j + 1] not in BOUNDARY:
            j += 1
        elif t in ("turn",) and verb in ("turn", "make", "do", "take") and angle is not None:
            j += 1  # "make a quarter turn"
        else:
            break
    d = s.defaults
    if angle is not None:
        return [(TURN, "", 0.0, 0.0, (sign or 1) * angle * times)], j
    if sign:
        deg = d.vague_turn_deg if vague else d.turn_deg
        return [(TURN, "", 0.0, 0.0, sign * math.radians(deg) * times)], j
    if around:
        return [(TURN_AROUND, "", 0.0, 0.0, math.pi)], j
    return None


# -- verb families -----------------------------------------------------------------------------------
def _motion(s: _State, i: int) -> Result:
    """go / move / walk / head / come / return / visit / step / back ...: a navigation ("to the
    kitchen", "home"), a relative move ("forward 2 m"), or a verb that leads into another ("go
    get the cup")."""
    toks, n = s.toks, s.n
    verb = toks[i]
    j = i + 1
    while j < n and toks[j] in ("over", "on", "yourself", "along", "right", "directly", "quickly", "now", "please",
                                "just", "all", "the", "way") and not (
            toks[j] == "right" and (j + 1 >= n or toks[j + 1] in BOUNDARY or toks[j + 1] not in TO_WORDS | HOME)):
        if toks[j] == "the" and not (j + 1 < n and toks[j + 1] == "way"):
            break
        if toks[j] == "on" and verb in ("go", "carry", "continue") and not (j + 1 < n and toks[j + 1] in TO_WORDS):
            break
        j += 1
    if s.at(j) in ("me", "us", "them", "him", "her") and s.at(j + 1) in TO_WORDS:
        j += 1  # "walk me to the kitchen"
    elif s.at(j) == "with" and s.at(j + 1) in ("me", "us", "them", "him", "her") and s.at(j + 2) in TO_WORDS:
        j += 2  # "come with me to the kitchen": company, not a place
    t = s.at(j)
    if verb == "back" and t in ("up", "off", "away", "out"):
        j += 1
        t = s.at(j)
    elif verb == "back" and not s.first and _done(s, j):
        return None  # "go to the bathroom and back": a return the grammar cannot place
    if t == "straight" and s.at(j + 1) in TO_WORDS | HOME | {"back"}:
        j += 1
        t = s.at(j)
    back = False
    if t == "back" and (s.at(j + 1) in TO_WORDS | HOME or (verb in ("come", "go", "get", "head") and s.at(j + 1) in (
            "over", "down", "up") and s.at(j + 2) in TO_WORDS)):
        back = True
        j += 1
        t = s.at(j)
    if t in ("over", "up", "down", "across", "round", "around", "through", "out") and s.at(j + 1) in TO_WORDS:
        j += 1
        t = s.at(j)
    if verb == "make":
        return _do(s, i)
    if verb == "get" and t not in TO_WORDS and t not in HOME and t != "back":
        return _pick(s, i)
    if t in ("2", "two", "too") and s.at(j + 1) in ("the", "your", "my", "our", "station"):
        t = "to"  # "go two the kitchen": a recogniser's "to" (a number needs a unit or a direction)
    if t == "for" and (q := read_quantity(s.toks, j + 1)) is not None and q.dimension == LENGTH:
        return _move(s, j, verb)  # "go straight for two metres": how far, not where
    if s.at(j + 1) in ("the", "your", "my", "our") and (t == "in" and verb in ("go", "come", "head", "move") or (
            t == "until" and verb in ("go", "come", "walk", "run", "head", "move", "drive"))):
        t = "to"  # "go in the kitchen", "walk until the entrance": said for "into", "up to"
    if t in TO_WORDS and t != "for" or (t == "for" and verb in ("head", "make", "go")):
        k = j + 1
        k2 = k
        while k2 < n and toks[k2] in ("the", "your", "my"):
            k2 += 1
        if s.at(k2) in ("left", "right", "front", "back", "rear") and (
                k2 + 1 >= n or toks[k2 + 1] not in ("of", "side", "hand", "wall", "door", "room")):
            return _move(s, k, verb)  # "move to the left"
        if k < n and toks[k] in ALL_VERBS and toks[k] not in ("back", "face", "stand", "hand", "end", "break"):
            return _clause(s, k)  # "go to find the cup"
        words, e = _np(s, k)
        return _go(s, _place(s, words), e)
    if t in HOME:
        return [(NAVIGATE, t, 0.0, 0.0, 0.0)], j + 1
    if t == "there" and (s.last_place or s.topic) and verb not in ("move", "step", "back"):
        return [(NAVIGATE, s.last_place or s.topic, 0.0, 0.0, 0.0)], j + 1  # "... and then go there again"
    if back or (verb == "come" and t in ("back", "here", "closer", "over", "")):
        return None  # "come back", "come here": towards the speaker, whom the grammar cannot place
    if verb in ("visit", "approach", "reach", "enter", "navigate", "goto"):
        words, e = _np(s, j)
        return _go(s, _place(s, words), e)
    if t in ALL_VERBS and t not in DIRECTIONS and verb in ("go", "come", "run", "hurry", "rush") and t not in (
            "stand", "back"):
        return _clause(s, j)  # "go get the bottle", "come wave"
    if t == "and" and s.at(j + 1) in ALL_VERBS and verb in ("go", "come"):
        return _clause(s, j + 1)  # "go and get the bottle"
    if verb == "face":
        return _turn_terms(s, j, verb)
    if verb == "go" and t in ("ahead", "on", "forth") and _done(s, j + 1):
        return None  # "go ahead", "go on": permission, not a direction
    if t in ("a", "an", "one", "two") and s.at(j + 1) in ("step", "steps") and verb == "take":
        pass
    return _move(s, j, verb, default_back=verb in ("back", "retreat", "reverse"))


def _guide(s: _State, i: int) -> Result:
    """lead / guide / escort / accompany / usher (me) (the way) to X: navigate_to_marker."""
    j = i + 1
    while s.at(j) in OBJECT_PRONOUNS or s.at(j) in ("the", "way", "back", "over", "our", "visitors", "guests"):
        j += 1
    if s.at(j) not in TO_WORDS:  # "escort our new guest to ...": whoever is guided, then where
        _, j = _np(s, j)
        while s.at(j) in ("the", "way", "back", "over"):
            j += 1
    if s.at(j) not in TO_WORDS:
        return None
    words, e = _np(s, j + 1)
    return _go(s, _place(s, words), e)


def _turn(s: _State, i: int) -> Result:
    """turn / rotate / spin / face ...: "turn left", "turn 90 degrees to the right", "turn around",
    "face the other way". ``None`` for "turn on the light" and "turn towards the door"."""
    verb = s.toks[i]
    return _turn_terms(s, i + 1, verb)


def _pick(s: _State, i: int) -> Result:
    """pick up / grab / get / fetch / bring / take / hand me ...: pick_up, with a source ("from
    the kitchen": go there first) or a destination ("to the workbench": go there after)."""
    toks, n = s.toks, s.n
    verb = toks[i]
    j = i + 1
    if verb == "pick":
        if s.at(j) in ("up", "out"):
            j += 1
        elif "up" not in s.toks[j:j + 8]:
            words, _ = _np(s, j)
            if not words or words[-1] in CHOICES:
                return None  # "pick a card": choosing, not lifting
    elif verb in ("lift", "raise"):
        k = j + 1 if s.at(j) in ("your", "both", "the", "my") else j
        if s.at(k) in BODY or s.at(k) in ("right", "left", "both") and s.at(k + 1) in BODY:
            return _raise(s, i)
    elif verb == "get":
        t = s.at(j)
        if t in ("going", "go", "moving", "move", "up", "down", "out", "ready", "closer", "away", "lost", "along",
                 "on", "off", "in", "inside", "started", "here", "over", "there", "a", "an", "rid", "it", "real",
                 "better", "well", "some", "started", "dressed", "to", "back", "home"):
            if t in ("to", "back", "home") or (t == "over" and s.at(j + 1) in TO_WORDS):
                return _motion(s, i)  # (_motion hands "get" without a destination back here)
            if t == "over":
                return None  # "get over it"
            if t not in ("a", "an", "it", "some"):
                return None
    elif verb in ("give", "hand", "pass"):
        k = j
        if s.at(k) in OBJECT_PRONOUNS and s.at(k) not in ("them", "you", "yourself"):
            k += 1
        elif s.at(k) == "over" and verb in ("hand", "pass"):
            j = k = k + 1  # "hand over the screwdriver"
        k2 = k + 1 if s.at(k) in DETERMINERS else k
        g = s.phrase_at(k2, _GESTURE_BY_FIRST)
        if g is not None:
            return [(GESTURE, GESTURE_PHRASES[g], 0.0, 0.0, 0.0)], _skip_gesture_tail(s, k2 + len(g))
    if verb in ("bring", "carry") and s.at(j) in ("me", "us", "them", "him", "her") and s.at(j + 1) in TO_WORDS:
        return _guide(s, i)  # "bring me to the kitchen"
    if verb in ("bring", "get", "fetch", "grab", "hand", "pass", "give", "find", "buy", "pour") and s.at(j) in (
            "me", "us", "him", "her") and j + 1 < n and toks[j + 1] not in BOUNDARY and toks[j + 1] not in (
            "to", "here", "over", "back"):
        j += 1
    elif s.at(j) in ("to", "for") and s.at(j + 1) in ("me", "us") and s.at(j + 2) in DETERMINERS:
        j += 2  # "bring to me the bottle": who it is for, said first
    words, e = _np(s, j)
    target = _object(s, words)
    if target is None or (verb == "take" and words[-1] in NP_BLOCK):
        return None  # "take a short break", "take a deep breath": idioms whatever the adjective
    targets = [target]
    more, e_more = _shared_list(s, e)
    if more:  # "fetch the cup and the bottle from the kitchen": the source is both objects'
        targets += more
        e = e_more
    if verb == "pick" and s.at(e) in ("up", "out"):
        e += 1
    if s.at(e) == "up" and verb in ("pick", "lift", "take", "scoop", "grab"):
        e += 1
    out: list[Spec] = []
    k = e
    while k < n and toks[k] in ("for", "me", "us", "please", "over", "here", "back", "and", "bring", "it", "up"):
        if toks[k] == "and" and not (s.at(k + 1) in ("bring", "carry", "take") and s.at(k + 2) in ("it", "them")):
            break
        k += 1
    if s.at(k) == "from" or (s.at(k) in ("off", "out") and s.at(k + 1) in ("of", "the")):
        k2 = k + 1 + (1 if s.at(k + 1) == "of" else 0)
        src_words, e2 = _np(s, k2)
        src = _place(s, src_words)
        if src is not None and src_words[-1] in SURFACES:
            src, e = None, e2  # "from the table": where the object lies, not where to go
        if src is not None and verb in ("bring", "get", "fetch", "grab", "take", "retrieve", "collect", "pick",
                                        "carry", "pass", "hand", "give"):
            out.append((NAVIGATE, src, 0.0, 0.0, 0.0))
            e = e2
            k = e2
    if not (words[0] in ("it", "them", "that", "this") and s.last_action == PICK and target == s.last_object):
        out += [(PICK, t, 0.0, 0.0, 0.0) for t in targets]  # "grab the apple and bring it to ...": picked already
    if s.at(k) in ("to", "into", "over", "towards", "toward") and verb in ("bring", "take", "carry", "deliver",
                                                                           "fetch", "get", "move"):
        k2 = k + 1 + (1 if s.at(k) == "over" and s.at(k + 1) == "to" else 0)
        dest_words, e2 = _np(s, k2)
        dest = " ".join(dest_words)
        if dest_words and dest not in OBJECT_PRONOUNS and dest not in ("here", "me", "us", "the user"):
            place = _place(s, dest_words)
            if place is not None:
                out.append((NAVIGATE, place, 0.0, 0.0, 0.0))
        e = e2
    return out, e


def _shared_list(s: _State, e: int) -> tuple[list[str], int]:
    """More objects after the first ("the cup and the bottle", "the cup, the book and the
    apple") when a source or destination follows the last one, which then applies to all:
    (the other objects, end). Without one the list is left to the ellipsis rule."""
    more: list[str] = []
    k = e
    while s.at(k) in (",", "and"):
        k += 1
        if s.at(k) == "and":
            k += 1
        if s.at(k) not in DETERMINERS:
            return [], e
        words, k2 = _np(s, k)
        obj = _object(s, words) if words else None
        if obj is None:
            return [], e
        more.append(obj)
        k = k2
    if more and (s.at(k) == "from" or s.at(k) in ("to", "into") and s.at(k + 1) in DETERMINERS | {"station"}):
        return more, k
    return [], e


def _find(s: _State, i: int, verb: str = "") -> Result:
    """find / locate / look for / search for / check for ...: find; "search the kitchen for the
    cup" goes to the kitchen first. ``None`` for "look left", "find out ...". ``verb`` overrides
    the word at ``i`` (a noun read as a verb: "have a peek for ...")."""
    toks, n = s.toks, s.n
    verb = verb or toks[i]
    j = i + 1
    area: str | None = None
    if verb in ("look", "hunt", "scan", "search", "seek", "track", "check"):
        while s.at(j) in ("around", "about", "out", "everywhere", "all", "over", "round"):
            j += 1
        if s.at(j) == "for":
            j += 1
        elif verb in ("search", "scan", "check"):
            if s.at(j) in ("in", "inside", "through", "of"):
                j += 1  # "search in the kitchen for ...", "have a search of the kitchen for ..."
            words, e = _np(s, j)
            area = _place(s, words)
            if area is None:
                return None
            if s.at(e) != "for":  # "search the kitchen": a place to search; "check the kitchen": vague
                return ([(FIND, area, 0.0, 0.0, 0.0)], e) if verb != "check" else None
            j = e + 1
        elif verb in ("track", "hunt") and s.at(j) == "down":
            j += 1
        elif verb in ("look", "hunt", "seek", "check"):
            return None
    elif verb == "find":
        if s.at(j) == "out":
            return None
        if s.at(j) == "your" and s.at(j + 1) == "way":
            return _way_to(s, j + 2)
        if s.at(j) in ("me", "us") and j + 1 < n and toks[j + 1] not in BOUNDARY and toks[j + 1] not in TRAILING:
            j += 1
        elif s.at(j) in ("to", "for") and s.at(j + 1) in ("me", "us") and s.at(j + 2) in DETERMINERS:
            j += 2  # "find for me the cup"
    elif verb in ("locate", "spot", "detect"):
        pass
    words, e = _np(s, j)
    if not words and s.at(e) == "and" and s.at(e + 1) in ALL_VERBS:
        after = _clause(s, e + 1)  # "locate and pick up the bottle": both verbs have the bottle
        if after is not None and after[0] and after[0][-1][1]:
            return [(FIND, after[0][-1][1], 0.0, 0.0, 0.0), *after[0]], after[1]
        return None
    if verb == "find" and words == ["me"]:
        target: str | None = "me"
    else:
        target = _object(s, words)
    if target is None:
        return None
    out: list[Spec] = []
    if area is not None:
        out.append((NAVIGATE, area, 0.0, 0.0, 0.0))
    out.append((FIND, target, 0.0, 0.0, 0.0))
    return out, e


def _find_noun(s: _State, i: int) -> Result:
    """A light verb with the noun of a find verb: "have a look for the keys", "take a quick look
    around for the cup", "do a search for the bottle": read as that find verb. ``None`` when no
    such noun follows ("take a look at this" has no "for": no object to find)."""
    k = i + 1
    if s.at(k) not in ("a", "an", "another"):
        return None
    k += 1
    if s.at(k) in ("quick", "little", "good", "proper", "careful", "fast", "short"):
        k += 1
    if s.at(k) not in FIND_NOUNS:
        return None
    m = k + 1
    while s.at(m) in ("around", "about", "round"):
        m += 1
    if s.at(m) == "for":
        return _find(s, k, "look")
    # "have a search of the kitchen for the cup", "take a look around the kitchen for the cup"
    return _find(s, m - 1 if s.at(m) in ("of", "in", "inside", "through") else k, "check")


def _way_to(s: _State, m: int) -> Result:
    """After "make your way" / "find your way": (over, back, ...) to PLACE."""
    while s.at(m) in ("over", "back", "down", "up", "across", "round", "around", "straight"):
        m += 1
    if s.at(m) not in TO_WORDS:
        return None
    words, e = _np(s, m + 1)
    target = _place(s, words)
    return ([(NAVIGATE, target, 0.0, 0.0, 0.0)], e) if target else None


def _stop(s: _State, i: int) -> Result:
    """stop / halt / freeze / wait / stay / hold on / never mind ...: stop. Reads to the next
    connector ("stop what you are doing and turn around")."""
    toks, n = s.toks, s.n
    verb = toks[i]
    j = i + 1
    nxt = s.at(j)
    if verb == "stand" and nxt not in ("still", "there", "by", "put", "here", "fast", "your", "right", "at", "in",
                                       "near", "beside", "inside"):
        return None
    if verb == "never" and nxt != "mind":
        return None
    if verb in ("stop", "halt") and nxt in ("me", "us", "him", "her", "them", "everyone", "everybody", "people"):
        return None  # "stop me if you've heard this one": someone else is stopped
    if verb == "forget" and nxt not in ("it", "that", "about", "everything", "this"):
        return None
    if verb == "cut" and nxt not in ("it", "that", "out"):
        return None
    if verb in ("hang", "hold") and nxt not in ("on", "it", "up", "still", "your", "position", "tight", "off",
                                                 "everything", "there"):
        return None
    if verb in ("end", "terminate", "kill", "interrupt") and nxt not in ("it", "that", "the", "this", "everything",
                                                                          "mission", "task", "now", "all"):
        return None
    if verb == "break" and nxt not in ("off",):
        return None
    if verb == "chill" and nxt not in ("out", ""):
        return None
    if verb == "e" and nxt != "stop":
        return None
    if verb == "emergency" and nxt not in ("stop", "halt", "brake", ""):
        return None
    if verb == "quit" and nxt not in ("it", "that", "moving", "move", "now", "", "please"):
        return None
    if verb in ("wait", "stay", "stand") and nxt in ("at", "by", "in", "near", "inside", "beside") and s.at(
            j + 1) in ("the", "your", "my", "our", "station"):
        words, e = _np(s, j + 1)  # "wait at the entrance": go there, then stay
        place = _place(s, words)
        if place is not None and words[-1] not in SURFACES:
            return [(NAVIGATE, place, 0.0, 0.0, 0.0), (STOP, "", 0.0, 0.0, 0.0)], _skip_rest(s, e)
    if verb == "stand" and nxt not in ("still", "there", "by", "put", "here", "fast", "your", "right"):
        return None  # "stand in line"
    while j < n and toks[j] not in BOUNDARY:
        if j > i + 1 and toks[j] in STRONG_VERBS and toks[j] not in ("move", "go", "stop", "turn", "walk"):
            break
        j += 1
    return [(STOP, "", 0.0, 0.0, 0.0)], j


VISIT_VERBS = frozenset({"stop", "swing", "drop", "come", "pop", "go", "pass", "nip", "call"})


def _visit_by(s: _State, i: int) -> Result:
    """ "stop by the kitchen", "swing by the workbench", "drop by station 3": a visit
    (navigate_to_marker). Only with a place after "by": "stand by" and "stop by 5" are not."""
    if s.at(i + 1) != "by" or s.at(i + 2) not in ("the", "your", "my", "our", "station"):
        return None
    words, e = _np(s, i + 2)
    place = _place(s, words)
    return ([(NAVIGATE, place, 0.0, 0.0, 0.0)], e) if place and words[-1] not in SURFACES else None


def _skip_gesture_tail(s: _State, j: int) -> int:
    """Words after a gesture that change nothing: "gesture", "with your hands", "at me", "to
    the camera", "for the visitors", "hello", "goodbye"."""
    toks, n = s.toks, s.n
    while j < n and toks[j] not in BOUNDARY:
        if toks[j] in STRONG_VERBS and toks[j] not in ("wave",) and j + 1 < n and toks[j + 1] not in BOUNDARY:
            break
        j += 1
    return j


def _gesture(s: _State, i: int) -> Result:
    """wave / clap / hug / shake hands / blow a kiss / raise your hands / put your arms down..."""
    toks = s.toks
    verb = toks[i]
    j = i + 1
    nxt = s.at(j)
    if verb == "wave":
        if nxt in ("goodbye", "bye") or s.at(j + 1) in ("bye",):
            pass
        if nxt in ("the", "a") and s.at(j + 1) in ("flag", "wand", "banner", "sign"):
            return None
        return [(GESTURE, "wave", 0.0, 0.0, 0.0)], _skip_gesture_tail(s, j)
    if verb in ("clap", "applaud"):
        return [(GESTURE, "clap", 0.0, 0.0, 0.0)], _skip_gesture_tail(s, j)
    if verb in ("hug", "cuddle", "embrace"):
        return [(GESTURE, "hug", 0.0, 0.0, 0.0)], _skip_gesture_tail(s, j)
    if verb == "say":  # "say hello with a wave"; saying alone is speech, not a gesture
        for k in range(j, min(j + 5, s.n)):
            if toks[k] == "with":
                m = k + 1 + (1 if s.at(k + 1) in DETERMINERS else 0)
                g = s.phrase_at(m, _GESTURE_BY_FIRST)
                if g is not None:
                    return [(GESTURE, GESTURE_PHRASES[g], 0.0, 0.0, 0.0)], _skip_gesture_tail(s, m + len(g))
            if toks[k] in BOUNDARY:
                break
        return None
    if verb == "greet":
        return [(GESTURE, "wave", 0.0, 0.0, 0.0)], _skip_gesture_tail(s, j)
    if verb == "reject":
        return [(GESTURE, "reject", 0.0, 0.0, 0.0)], _skip_gesture_tail(s, j)
    if verb == "shake":
        for k in range(j, min(j + 4, s.n)):
            if toks[k] in ("hand", "hands"):
                return [(GESTURE, "shake hand", 0.0, 0.0, 0.0)], _skip_gesture_tail(s, k + 1)
            if toks[k] in BOUNDARY:
                break
        return None
    if verb in ("kiss", "blow"):
        k = j
        while k < s.n and toks[k] in ("me", "us", "a", "an", "the", "everyone", "them", "him", "her", "some", "big"):
            k += 1
        if verb == "kiss" or s.at(k) in ("kiss", "kisses"):
            name = "two hand kiss"
            tail = _skip_gesture_tail(s, k + (1 if verb == "blow" else 0))
            words = toks[k:tail]
            if "left" in words:
                name = "left kiss"
            elif "right" in words:
                name = "right kiss"
            return [(GESTURE, name, 0.0, 0.0, 0.0)], tail
        return None
    if verb in ("raise", "put", "lift"):
        return _raise(s, i)
    if verb in ("lower", "drop", "relax", "release", "rest"):
        k = j + 1 if nxt in ("your", "both", "the", "my") else j
        if s.at(k) in BODY or (s.at(k) == "arm" or (s.at(k) in ("both",) and s.at(k + 1) in BODY)):
            return [(GESTURE, "release arm", 0.0, 0.0, 0.0)], _skip_gesture_tail(s, k + 1)
        return None
    return None


def _raise(s: _State, i: int) -> Result:
    """raise / lift / put + your hands: "hands up", "right hand up" or (down) "release arm"."""
    toks = s.toks
    verb = toks[i]
    j = i + 1
    side = ""
    plural = False
    k = j
    while k < s.n and toks[k] in ("your", "both", "the", "my", "right", "left", "two"):
        if toks[k] in ("right", "left"):
            side = toks[k]
        if toks[k] in ("both", "two"):
            plural = True
        k += 1
    if s.at(k) not in BODY:
        return None
    plural = plural or toks[k] in ("hands", "arms")
    k += 1
    down = False
    if verb == "put":
        if s.at(k) in ("down",):
            down = True
        elif s.at(k) not in ("up", "in", "into", "high", "above", "over"):
            return None
    if down:
        return [(GESTURE, "release arm", 0.0, 0.0, 0.0)], _skip_gesture_tail(s, k)
    if side == "left" and not plural:
        return None  # the library has no left-hand-up gesture
    name = "hands up" if plural else "right hand up"
    return [(GESTURE, name, 0.0, 0.0, 0.0)], _skip_gesture_tail(s, k)


def _do(s: _State, i: int) -> Result:
    """do / make / perform / give / show / take / throw: a gesture ("do a high five", "show me a
    heart"), a turn ("make a u-turn", "do a 180", "take a left", "make a quarter turn"), a way
    ("make your way to the kitchen", "show me the way to the kitchen"), or for give/take/show the
    pick and navigation readings."""
    toks, n = s.toks, s.n
    verb = toks[i]
    j = i + 1
    if verb in FIND_NOUN_LEADS and (got := _find_noun(s, i)) is not None:
        return got
    if verb == "take" and s.at(j) in ("me", "us", "him", "her", "them") and s.at(j + 1) in TO_WORDS:
        words, e = _np(s, j + 2)
        target = _place(s, words)
        return ([(NAVIGATE, target, 0.0, 0.0, 0.0)], e) if target else None
    if verb == "show" and s.at(j) in ("me", "us", "them", "him", "her", "everyone"):
        k = j + 1
        if s.at(k) in TO_WORDS:
            return _guide(s, i)  # "show me to the bathroom"
        if s.at(k) == "the" and s.at(k + 1) == "way" and s.at(k + 2) in TO_WORDS:
            words, e = _np(s, k + 3)
            target = _place(s, words)
            return ([(NAVIGATE, target, 0.0, 0.0, 0.0)], e) if target else None
        if s.at(k) == "where" and k + 1 < n:
            words, e = _np(s, k + 1 + (1 if s.at(k + 1) in ("the",) else 0))
            if s.at(e) == "is" or s.at(e) == "are":
                target = _place(s, words)
                return ([(NAVIGATE, target, 0.0, 0.0, 0.0)], e + 1) if target else None
            return None
    if s.at(j) in ("me", "us", "him", "her", "them", "everyone", "everybody", "the", "our", "you"):
        if s.at(j) in ("the", "our") and s.at(j + 1) in ("guests", "visitors", "kids", "children", "audience",
                                                         "crowd", "people", "group", "class", "team"):
            j += 2
        elif s.at(j) not in ("the", "our"):
            j += 1
    k = j
    while k < n and toks[k] in ("a", "an", "the", "your", "some", "another", "that", "this", "my", "nice", "little",
                                "quick", "cool", "famous", "special", "full", "lovely", "big"):
        if toks[k] in ("full",) or (toks[k] in ("big", "little") and s.at(k + 1) in GESTURE_NOUNS):
            break
        k += 1
    g = s.phrase_at(k, _GESTURE_BY_FIRST)
    if g is not None and not (toks[k] in ("five",) and verb not in ("give",)):
        if toks[k] in ("hand",) and len(g) == 2 and verb != "give":
            pass
        return [(GESTURE, GESTURE_PHRASES[g], 0.0, 0.0, 0.0)], _skip_gesture_tail(s, k + len(g))
    if verb in ("do", "make", "perform", "take", "try", "pull", "execute", "throw"):
        t = s.at(k)
        if t in ("u", "you") and s.at(k + 1) in ("turn", "turnaround"):
            return [(TURN_AROUND, "", 0.0, 0.0, math.pi)], k + 2
        if t == "about" and s.at(k + 1) in ("face", "turn"):
            return [(TURN_AROUND, "", 0.0, 0.0, math.pi)], k + 2
        if t in ("turnaround", "one80"):
            return [(TURN_AROUND, "", 0.0, 0.0, math.pi)], k + 1
        if verb != "take" and (t == "180" or (t == "one" and s.at(k + 1) == "eighty")) and s.at(
                k + (1 if t == "180" else 2)) not in UNITS:
            return [(TURN_AROUND, "", 0.0, 0.0, math.pi)], k + (1 if t == "180" else 2)
        if t in ("left", "right") and (s.at(k + 1) in ("turn", "") or s.at(k + 1) in BOUNDARY or s.at(
                k + 1) in TRAILING):
            return [(TURN, "", 0.0, 0.0, ROTATIONS[t] * math.radians(s.defaults.turn_deg))], k + (
                2 if s.at(k + 1) == "turn" else 1)
        if verb in ("make", "do") and (t == "way" or (t == "your" and s.at(k + 1) == "way")):
            return _way_to(s, k + (1 if t == "way" else 2))
        if verb in ("take", "make", "do") and (t in STEP_WORDS or s.at(k + 1) in STEP_WORDS or s.at(
                k + 2) in STEP_WORDS):
            got = _move(s, j, "step")
            at = next(m for m in range(k, k + 3) if toks[m] in STEP_WORDS)
            if got is None and toks[at] in ("step", "pace"):  # "take a small step to the left": one step that way
                got = _move(s, at + 1, "step")
                if got is None and _done(s, at + 1):  # "take a small step": forward, like "take a step"
                    got = [(MOVE, "", s.defaults.step_m, 0.0, 0.0)], at + 1
            return got
        # "make a quarter turn to the left", "do a full turn", "do a 360"
        k0 = j
        while k0 < n and toks[k0] in ("a", "an", "the"):
            if s.at(k0 + 1) in _NUMBER_STARTS or s.at(k0 + 1)[:1].isdigit() or s.at(k0 + 1) in ("full", "complete",
                                                                                                  "whole", "turn"):
                break
            k0 += 1
        got = _turn_terms(s, k0, verb)
        if got is not None and verb == "take" and not any(w in ROTATIONS or w in UNITS for w in toks[k0:got[1]]):
            got = None  # "take five": a break; "take a left", "take a quarter turn" say how they turn
        if got is not None and (got[0][0][0] != TURN_AROUND or s.at(k0) in AROUND):
            return got
        if verb in ("do", "make") and s.at(k) == "spin":
            return [(TURN, "", 0.0, 0.0, 2 * math.pi)], k + 1
        return _pick(s, i) if verb == "take" else None
    if verb in ("give", "show"):
        if verb == "give" and s.at(i + 1) in ("me", "us") or verb == "give" and s.at(i + 1) in DETERMINERS:
            return _pick(s, i)
        return None
    return None


# -- clauses -----------------------------------------------------------------------------------------
def _family(verb: str) -> Callable[[_State, int], Result] | None:
    return _DISPATCH.get(verb)


_DISPATCH: dict[str, Callable[[_State, int], Result]] = {}
for _verbs, _reader in ((MOTION_VERBS, _motion), (TURN_VERBS, _turn), (PICK_VERBS, _pick), (FIND_VERBS, _find),
                        (STOP_VERBS, _stop), (GESTURE_VERBS, _gesture), (LIGHT_VERBS, _do)):
    _DISPATCH.update(dict.fromkeys(_verbs, _reader))
_DISPATCH["get"] = _motion  # "get to the kitchen" / "get me a cup" (it hands over to _pick)
_DISPATCH["take"] = _take = _do  # "take me to", "take a step", "take a left", else pick
_DISPATCH["make"] = _do
_DISPATCH["give"] = _do
_DISPATCH["raise"] = _gesture
_DISPATCH["lift"] = _pick
_DISPATCH.update(dict.fromkeys(GUIDE_VERBS, _guide))
_DISPATCH["have"] = _find_noun  # "have a look for ..." (and nothing else: "have a seat")


STOP_PHRASES: tuple[tuple[str, ...], ...] = (
    ("thats", "enough"), ("that", "is", "enough"), ("enough",), ("emergency", "stop"), ("e", "stop"), ("whoa",),
    ("woah",), ("never", "mind"), ("forget", "it"), ("no", "stop"), ("not", "now"), ("dont", "move"),
    ("do", "not", "move"), ("dont", "go", "anywhere"), ("do", "not", "go", "anywhere"), ("no", "no"),
    ("no", "more"), ("stop",), ("halt",), ("freeze",), ("red", "light"), ("hands", "off"), ("easy",),
    ("steady",), ("dont", "walk"), ("dont", "do", "anything"), ("dont", "do", "that"), ("stop", "it"),
)
_STOP_BY_FIRST: dict[str, tuple[tuple[str, ...], ...]] = {}
for _s in sorted(STOP_PHRASES, key=lambda p: (-len(p), p)):
    _STOP_BY_FIRST[_s[0]] = _STOP_BY_FIRST.get(_s[0], ()) + (_s,)
TURN_IDIOMS: tuple[tuple[str, ...], ...] = (("about", "face"), ("about", "turn"), ("u", "turn"), ("one", "eighty"),
                                            ("180",), ("turnaround",), ("other", "way"), ("the", "other", "way"))
_IDIOM_BY_FIRST: dict[str, tuple[tuple[str, ...], ...]] = {}
for _t in sorted(TURN_IDIOMS, key=lambda p: (-len(p), p)):
    _IDIOM_BY_FIRST[_t[0]] = _IDIOM_BY_FIRST.get(_t[0], ()) + (_t,)


def _polite(s: _State, i: int) -> int:
    """Index after polite openers ("could you please", "would you mind", "I want you to",
    "let's", "you", "please") that come before the verb."""
    toks, n = s.toks, s.n
    for _ in range(8):
        if i >= n:
            break
        t = toks[i]
        p = s.phrase_at(i, _POLITE_BY_FIRST) if t in _POLITE_BY_FIRST else None
        if p is None:
            if t in MODALS and i + 1 < n and toks[i + 1] == "you":
                i += 2
                continue
            if t == "you" and i + 1 < n and toks[i + 1] in ALL_VERBS and toks[i + 1] not in ("look", "do", "stand",
                                                                                             "back", "hold"):
                i += 1
                continue
            break
        if p == ("right",) and (i + 1 >= n or toks[i + 1] in BOUNDARY or toks[i + 1] in _NUMBER_STARTS or toks[
                i + 1][:1].isdigit() or toks[i + 1] in ("by", "about", "turn")):
            break  # "right" is a direction here
        if p in (("start",), ("begin",), ("keep",)) and not (i + 1 < n and toks[i + 1] in ALL_VERBS):
            break
        if p in _BEFORE_A_VERB_ONLY and s.at(i + len(p)) not in ALL_VERBS:
            break  # "like" is a filler only before a verb: "could you like go to the kitchen"; "help me find"
        i += len(p)
    return i


# polite openers only when a verb follows: "could you like go", "help me find", "mind getting"
_BEFORE_A_VERB_ONLY = frozenset({("next",), ("like",), ("help", "me"), ("help", "us"), ("please", "to"), ("mind",),
                                 ("you", "mind")})

REQUESTS: tuple[tuple[str, ...], ...] = tuple(
    (m, who, *please, v) for m in ("can", "could", "may") for who in ("i", "we") for please in ((), ("please",))
    for v in ("have", "get"))
WANTS: tuple[tuple[str, ...], ...] = (("i", "want"), ("i", "would", "like"), ("id", "like"), ("i", "need"),
                                      ("we", "want"), ("id", "love"), ("i", "would", "love"), ("we", "would", "like"),
                                      ("wed", "like"), ("i", "could", "use"), ("i", "could", "do", "with"))
# wishes that ask for an object when a plain noun phrase ends the clause ("I'd like the apple,
# please"); "I want ..." and "I need ..." stay gestures only ("I need the bathroom")
WANTS_OBJECT = frozenset({("i", "would", "like"), ("id", "like"), ("we", "would", "like"), ("wed", "like"),
                          ("i", "could", "use")})
_REQUEST_BY_FIRST: dict[str, tuple[tuple[str, ...], ...]] = {}
for _r in sorted(REQUESTS + WANTS, key=lambda p: (-len(p), p)):
    _REQUEST_BY_FIRST[_r[0]] = _REQUEST_BY_FIRST.get(_r[0], ()) + (_r,)


def _request(s: _State, i: int) -> Result:
    """ "can I have a hug" / "could we get the bottle" (gesture or pick_up) and "I want a high
    five" / "I'd love a hug" (gestures only: "I want the kitchen clean" is no command)."""
    p = s.phrase_at(i, _REQUEST_BY_FIRST)
    if p is None:
        return None
    j = i + len(p)
    k = j + 1 if s.at(j) in DETERMINERS else j
    g = s.phrase_at(k, _GESTURE_BY_FIRST)
    if g is not None and (len(g) > 1 or g[0] != "five"):
        return [(GESTURE, GESTURE_PHRASES[g], 0.0, 0.0, 0.0)], _skip_gesture_tail(s, k + len(g))
    if s.at(j) in ("to", "some", "help", "a") and s.at(j + 1) in ("help", "hand", "minute", "word"):
        return None
    if p in WANTS and not (p in WANTS_OBJECT and s.at(j) in ("the", "a", "an", "that", "this", "my")):
        return None
    words, e = _np(s, j)
    if p in WANTS and (not _done(s, e) or any(len(w) > 4 and w.endswith("ed") for w in words[1:])):
        return None  # "I'd like the kitchen cleaned": no object handed over
    target = _object(s, words)
    return ([(PICK, target, 0.0, 0.0, 0.0)], e) if target else None


# the speaker as the subject of a gesture the robot shares: "let me shake your hand", "can I hug
# you", "may we give you a high five" ask the robot for that gesture; other "can I ..." are
# questions about the speaker ("can I go to the kitchen?")
SPEAKER_OPENERS: tuple[tuple[str, ...], ...] = (
    ("let", "me"), ("can", "i"), ("could", "i"), ("may", "i"), ("can", "we"), ("could", "we"), ("may", "we"))
_SPEAKER_BY_FIRST: dict[str, tuple[tuple[str, ...], ...]] = {}
for _o in SPEAKER_OPENERS:
    _SPEAKER_BY_FIRST[_o[0]] = _SPEAKER_BY_FIRST.get(_o[0], ()) + (_o,)
RECIPROCAL = frozenset({"hug", "shake hand", "high five"})  # gestures made with someone


def _reciprocal(s: _State, i: int) -> Result:
    """ "let me shake your hand" / "can I give you a hug": the robot's half of a shared gesture."""
    p = s.phrase_at(i, _SPEAKER_BY_FIRST)
    if p is None:
        return None
    j = i + len(p)
    while s.at(j) in ("please", "just"):
        j += 1
    if j >= s.n or (s.toks[j] not in GESTURE_VERBS and s.toks[j] not in LIGHT_VERBS and s.toks[j] != "high"):
        return None
    got = _clause(s, j)
    if got is None or any(a != GESTURE or tg not in RECIPROCAL for a, tg, *_ in got[0]):
        return None
    return got


def _opens_conversation(s: _State, i: int) -> bool:
    """Whether the clause at ``i`` opens like a question or statement (so the sentence is
    conversation to its end): wh-words, auxiliaries, subjects, wishes ("would you like")."""
    toks, n = s.toks, s.n
    t = toks[i]
    if t in WH or t in AUX or t in SUBJECTS:
        return True
    if t == "do" and i + 1 < n and toks[i + 1] in ("you", "i", "we", "they", "it", "he", "she", "not"):
        return True
    if t in MODALS and i + 1 < n and toks[i + 1] != "you":
        return True
    if t in _WISH_BY_FIRST and s.phrase_at(i, _WISH_BY_FIRST) is not None:
        return True
    return t == "you" and not (i + 1 < n and toks[i + 1] in ALL_VERBS)


def _clause(s: _State, i: int) -> Result:
    """One clause at ``i`` (after a connector): polite openers, then a verb phrase, or one of the
    verbless forms (stop phrases, "about face", a gesture name, an elliptic direction or noun
    phrase continuing the clause before)."""
    toks, n = s.toks, s.n
    if toks[i] in _REQUEST_BY_FIRST and (got := _request(s, i)) is not None:
        return got
    if toks[i] in _SPEAKER_BY_FIRST and (got := _reciprocal(s, i)) is not None:
        return got
    if toks[i] in _WISH_BY_FIRST and s.phrase_at(i, _WISH_BY_FIRST) is not None:
        return None
    i = _polite(s, i)
    if i >= n:
        return None
    t = toks[i]
    if s.at(i + 1) in COPULA or (s.at(i + 2) in COPULA and s.at(i + 1) not in BOUNDARY):
        return None  # "stop signs are red", "turn left is wrong": the verb is a noun here
    if t in VISIT_VERBS and s.at(i + 1) == "by" and (got := _visit_by(s, i)) is not None:
        return got
    sp = s.phrase_at(i, _STOP_BY_FIRST) if t in _STOP_BY_FIRST else None
    if sp is not None and (len(sp) > 1 or t in ("stop", "halt", "freeze", "enough", "whoa", "woah")):
        if t in ("stop", "halt", "freeze"):
            return _stop(s, i)
        j = i + len(sp)
        if t in ("easy", "steady", "enough") and not _done(s, j):
            return None
        if sp[0] in ("dont", "do") and (s.at(j) in TO_WORDS or s.at(j) in ("near", "over", "across", "through")):
            return None  # "don't walk into the bathroom": a negated command, not "don't move"
        while j < n and toks[j] not in BOUNDARY:
            j += 1
        return [(STOP, "", 0.0, 0.0, 0.0)], j
    if t in ("dont", "never") or (t == "do" and s.at(i + 1) == "not") or t == "not":
        return None  # a negated command is no command
    handler = _DISPATCH.get(t)
    if handler is not None:
        got = handler(s, i)
        if got is not None:
            return got
        if t not in DIRECTIONS and t not in ("back",):
            return None
    return _verbless(s, i)


def _verbless(s: _State, i: int) -> Result:
    """Clauses with no verb: "about face", "high five!", "forward two metres", "left 90",
    and ellipsis after a connector ("... and the bathroom", "... then right")."""
    toks, n = s.toks, s.n
    t = toks[i]
    idiom = s.phrase_at(i, _IDIOM_BY_FIRST)
    if idiom is not None and _done(s, i + len(idiom)):
        return [(TURN_AROUND, "", 0.0, 0.0, math.pi)], i + len(idiom)
    k = i + 1 if t in DETERMINERS and i + 1 < n else i
    g = s.phrase_at(k, _GESTURE_BY_FIRST)
    if g is not None and (len(g) > 1 or g[0] not in ("five", "kiss", "waves", "kisses")) and _done(s, k + len(g)):
        end = k + len(g)
        while end < n and toks[end] in GESTURE_NOUNS:
            end += 1
        return [(GESTURE, GESTURE_PHRASES[g], 0.0, 0.0, 0.0)], end
    last = s.last_action
    if last == NAVIGATE and t in TO_WORDS and t != "for" and i + 1 < n:  # "... then to the kitchen"
        k = i + 1
        while k < n and toks[k] in ("the", "your", "my"):
            k += 1
        if s.at(k) not in DIRECTIONS:
            words, j = _np(s, i + 1)
            target = _place(s, words)
            if target is not None and _done(s, j) and s.at(j) not in OBJECT_PRONOUNS:  # "(sorry) to bother you"
                return [(NAVIGATE, target, 0.0, 0.0, 0.0)], j
            return None
    if last == NAVIGATE and word_value(t) is not None and (num := _numbered(s.last_place)) and _done(s, i + 1):
        return [(NAVIGATE, f"{num[0]} {t}", 0.0, 0.0, 0.0)], i + 1  # "go to station 1, then 2"
    if t in DIRECTIONS or t in ROTATIONS or t in ("anti", "counter") or t[0].isdigit() or t in _NUMBER_STARTS or (
            t in ("to", "by") and s.at(i + 1) in ("the", "your", "left", "right")):
        if s.first or last in (MOVE, TURN, TURN_AROUND):
            turnish = last in (TURN, TURN_AROUND)
            if not turnish and s.first:
                direction, amount, dim, vague, j = _motion_terms(s, i)
                if amount is None and not vague and direction in (LEFT, RIGHT) and t in ("left", "right"):
                    return None  # "right." alone is an acknowledgement as often as a command
                turnish = dim == ANGLE or (direction in (LEFT, RIGHT) and (amount is None or (
                    dim == "" and amount > MAX_BARE_SIDESTEP_M)))  # "left 90": degrees, never 90 m
            got = _turn_terms(s, i, "turn") if turnish else _move(s, i, "move")
            if got is not None and _done(s, got[1]):
                return got
        return None
    if last in (NAVIGATE, PICK, FIND) and t not in WH and t not in AUX and (t not in SUBJECTS or t in DETERMINERS) and (
            not s.subordinate):  # "... and when you're ready, wave": "ready" is no second place
        words, j = _np(s, i)
        if not words or not _done(s, j) or any(w in DETERMINERS for w in words[1:]):
            return None  # "... and close the door": a verb and its object, not a second place
        target = _place(s, words) if last == NAVIGATE else _object(s, words)
        if target is None:
            return None
        return [(last, target, 0.0, 0.0, 0.0)], j
    return None


def _topic(s: _State, i: int) -> bool:
    """A first clause that is only a noun phrase before a comma ("the kitchen, please go there")
    becomes what "there" and "it" mean; True when it was one."""
    if not s.first or s.toks[i] not in DETERMINERS:
        return False
    words, j = _np(s, i)
    if s.at(j) != "," or not words or words[0] in SUBJECTS or any(w in COPULA or w in AUX for w in words):
        return False
    s.topic = " ".join(words)
    return True


# what a speaker says before correcting the clause just said: "go to the kitchen, no, the
# bathroom", "pick up the cup, sorry, I mean the bottle", "turn left, no wait, right"
CORRECTIONS: tuple[tuple[str, ...], ...] = (
    ("no",), ("no", "wait"), ("wait", "no"), ("sorry",), ("i", "mean"), ("i", "meant"), ("oops",),
    ("or", "rather"), ("rather",), ("make", "that"), ("make", "it"), ("scratch", "that"), ("correction",),
    ("my", "mistake"), ("my", "bad"), ("not", "that"), ("i", "said"),
)
_CORRECTION_BY_FIRST: dict[str, tuple[tuple[str, ...], ...]] = {}
for _c in sorted(CORRECTIONS, key=lambda c: (-len(c), c)):
    _CORRECTION_BY_FIRST[_c[0]] = _CORRECTION_BY_FIRST.get(_c[0], ()) + (_c,)


def _connector(s: _State, i: int) -> tuple[str, int] | None:
    """A connector at ``i``: ("next", end), ("reorder", end) for "but first", ("or", end)."""
    t = s.toks[i]
    if t == "to" and i + 1 < s.n and s.toks[i + 1] in ALL_VERBS:
        return "next", i + 1
    if t == "or":
        return "or", i + 1
    if t not in _CONNECTORS_BY_FIRST:
        return None
    c = s.phrase_at(i, _CONNECTORS_BY_FIRST)
    if c is None:
        return None
    return ("reorder" if c in REORDER else "next"), i + len(c)


def _skip_rest(s: _State, j: int) -> int:
    """After a clause: skip words the grammar does not use ("at the door", "quickly") up to the
    next connector, a purpose "to <verb>", or a new verb that starts a command."""
    toks, n = s.toks, s.n
    condition = False  # after "until", "unless", "if", "while": a verb is part of the condition
    while j < n:
        t = toks[j]
        if t in BOUNDARY and not (condition and t in ("when", "once", "after", "before")):
            break
        if t in CONDITIONS:
            condition = True
        elif not condition:
            if t in _CORRECTION_BY_FIRST and s.phrase_at(j, _CORRECTION_BY_FIRST) is not None:
                break  # "go to the kitchen no the bathroom"
            if t == "to" and j + 1 < n and toks[j + 1] in ALL_VERBS and toks[j + 1] not in ("back", "hand", "face"):
                break
            if t in STRONG_VERBS and toks[j - 1] not in DETERMINERS and toks[j - 1] != "to":
                break
            if (t, s.at(j + 1)) in VERB_PARTICLES and toks[j - 1] not in DETERMINERS and toks[j - 1] != "to":
                break
        j += 1
    return j


class Grammar:
    """Parses command text (what follows the wake phrase) into TaskIntents.

    ``vocatives`` are extra words that end a noun phrase (the robot's name: "go to the kitchen,
    Stuart" must not look for a "kitchen stuart"); ``defaults`` the amounts used when none is
    said."""

    def __init__(self, *, defaults: Defaults | None = None, vocatives: Iterable[str] = ()) -> None:
        self.defaults = defaults or Defaults()
        self.stop_words = NP_STOP | frozenset(v.lower() for v in vocatives)

    def parse(self, text: str) -> list[TaskIntent]:
        """The intents in ``text``, in the order they are to be done; [] when it holds no command."""
        tokens = tokenize(text)
        out = self.parse_tokens(text, tokens)
        if not out and "." in tokens.toks:  # "go. to. the kitchen.": a recogniser's stray periods
            out = self.parse_tokens(text, tokens.without("."))
        return out

    def parse_tokens(self, text: str, tokens: Tokens) -> list[TaskIntent]:
        """Like :meth:`parse` on the tokens :func:`tokenize` made of ``text``."""
        toks = list(tokens.toks)  # a past verb after "once you've" may be replaced by its base form
        s = _State(toks, len(toks), self.defaults, self.stop_words)
        n = s.n
        out: list[TaskIntent] = []
        i = 0
        dead = False  # the sentence opened as a question or statement
        reorder_at: int | None = None  # "X but first Y": Y's intents go before X's
        correct_at: int | None = None  # "X, no, Y": Y's intents replace X's
        clause_end = -1  # where the last clause ended: "X after you Y" has no connector between
        hold = False  # "before you Y, X": Y's intents wait ...
        held: list[TaskIntent] = []  # ... here until X's are in
        while i < n:
            t = toks[i]
            if t in HARD_STOPS:
                dead = False
                i += 1
                continue
            if out and not dead and t in _CORRECTION_BY_FIRST and (c := s.phrase_at(i, _CORRECTION_BY_FIRST)):
                correct_at = len(out) - _last_clause_len(out)  # "go to the kitchen, no, the bathroom"
                i += len(c)
                continue
            con = _connector(s, i)
            if con is not None:
                kind, i = con
                if kind == "or":  # "the kitchen or the bathroom": a choice is not a plan
                    while i < n and toks[i] not in HARD_STOPS:
                        i += 1
                elif kind == "reorder" and out:
                    reorder_at = len(out) - _last_clause_len(out)
                continue
            if dead and toks[i - 1] == "," and (t == "please" or (t in MODALS and s.at(i + 1) == "you") or (
                    t in ("stop", "halt", "freeze") and _done(s, i + 1))):
                dead = False  # "I lost my keys, can you help me find them?", "is enough, stop": said to the robot
            if dead:
                i += 1
                continue
            subordinate = False
            attached = bool(out) and i == clause_end
            if t == "before" and i + 1 < n and (toks[i + 1] in ("you", "u") or toks[i + 1] in ALL_VERBS):
                i += 2 if toks[i + 1] in ("you", "u") else 1
                hold = not attached  # "before you go, wave": the wave first; "wave before you go": in order
                if i >= n:
                    break
            if t == "as" and s.at(i + 1) == "soon" and s.at(i + 2) == "as" and s.at(i + 3) in (
                    "you", "youve", "youre", "u"):
                i += 2
                t = "once"  # "as soon as you get to the kitchen": like "once you ..."
            if t in SUBORDINATORS and i + 1 < n and (toks[i + 1] in ("you", "youve", "youre", "u") or (
                    t == "after" and toks[i + 1] in ALL_VERBS)):
                # "when you find it, pick it up": the clause says what happens first; it is kept
                # unless it repeats the intent just before ("look for the bottle and when you
                # find it ...")
                perfect = toks[i + 1] == "youve" or t == "once"
                i += 2 if toks[i + 1] in ("you", "youve", "youre", "u") else 1
                subordinate = True
                if t == "after" and attached:  # "go to the kitchen after you wave": the wave first
                    reorder_at = len(out) - _last_clause_len(out)
                if i < n and toks[i] == "have" and toks[i - 1] == "you":
                    i += 1  # "once you have picked up ..."
                    perfect = True
                if i >= n:
                    break
                if perfect and toks[i] in PAST:
                    toks[i] = PAST[toks[i]]  # "when you've found it": the verb ("when you went": a story)
            start = i
            got = _arrival(s, i) if subordinate and t != "if" else None
            if got is None:
                s.subordinate = subordinate
                got = _clause(s, i)
                s.subordinate = False
            if got is None:
                correct_at = reorder_at = None  # "go to the kitchen. no need to hurry": nothing to correct with
                hold = False
                if subordinate and t != "if":  # "when you are ready go to the kitchen": a time, no question
                    i = _skip_rest(s, i + 1)
                    s.first = False
                    continue
                if _opens_conversation(s, i) and not _topic(s, i):
                    dead = True
                i += 1
                while i < n and toks[i] not in BOUNDARY:
                    i += 1
                s.first = False
                continue
            specs, j = got
            j = max(j, i + 1)
            if not specs:  # "grab the cup and hand it to me": the handing over adds nothing
                s.first = False
                i = clause_end = _skip_rest(s, j)
                continue
            if s.at(j) in COPULA and not subordinate:  # "going to the kitchen was fun": a subject, so a statement
                dead = True
                correct_at = reorder_at = None
                hold = False
                i = j
                continue
            if subordinate and out and [(it.action, it.target) for it in out[-len(specs):]] == [
                    (a, tg) for a, tg, *_ in specs]:
                s.first = False
                i = _skip_rest(s, j)
                continue
            a, b = tokens.span(start, min(j, n) - 1)
            raw = text[a:b]
            made = [TaskIntent(a, tg, x, y, yaw, raw) for a, tg, x, y, yaw in specs]
            if hold:
                held, hold = made, False
            elif correct_at is not None:
                out[correct_at:] = made
                correct_at = None
            elif reorder_at is not None:
                out[reorder_at:reorder_at] = made
                reorder_at = None
            else:
                out.extend(made)
            if held and made is not held:
                out.extend(held)
                held = []
            for act, tg, *_ in specs:
                if act in (PICK, FIND) and tg not in ("me", "it"):
                    s.last_object = tg
                elif act == NAVIGATE:
                    s.last_place = tg
            s.last_action = specs[-1][0]
            s.first = False
            i = clause_end = _skip_rest(s, j)
        return _dedupe_stops(out + held)


def _arrival(s: _State, i: int) -> Result:
    """After "when you" / "once you": being somewhere is getting there ("once you're at the
    workbench, pick up the screwdriver", "when you arrive in the kitchen ..."): navigate_to_marker,
    dropped like any subordinate clause when it repeats the navigation before it. (After "if"
    it is a condition, not a plan.)"""
    if s.at(i) in ("are", "re", "arrive", "arrived", "get", "got"):
        i += 1  # "when you are at ...", "once you arrive at ..."
    if s.at(i) not in ("at", "in", "inside", "by", "near"):
        return None
    words, e = _np(s, i + 1)
    place = _place(s, words)
    return ([(NAVIGATE, place, 0.0, 0.0, 0.0)], e) if place and words[-1] not in SURFACES else None


def _last_clause_len(out: list[TaskIntent]) -> int:
    """How many of the last intents came from the last clause (same raw_text)."""
    if not out:
        return 0
    raw = out[-1].raw_text
    k = 0
    for it in reversed(out):
        if it.raw_text != raw:
            break
        k += 1
    return k


def _dedupe_stops(out: list[TaskIntent]) -> list[TaskIntent]:
    """ "stop, stop, stop!" is one stop."""
    if len(out) < 2:
        return out
    kept = [out[0]]
    for it in out[1:]:
        if it.action == STOP and kept[-1].action == STOP:
            continue
        kept.append(it)
    return kept


_DEFAULT = Grammar()


def parse_command(text: str) -> list[TaskIntent]:
    """The intents in command ``text`` with the default grammar (see :class:`Grammar`)."""
    return _DEFAULT.parse(text)
