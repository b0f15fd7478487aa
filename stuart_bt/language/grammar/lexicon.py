"""The words the grammar knows, as data: word classes, phrase tables (each also indexed by its
first word, for a fast longest match), the verbs of each family with their ing- and past forms.
Changing what the robot understands starts here; the readers only say how words combine.
"""

from __future__ import annotations

from collections.abc import Iterable


def by_first(phrases: Iterable[tuple[str, ...]]) -> dict[str, tuple[tuple[str, ...], ...]]:
    """Phrases indexed by their first word, in the order given (longest first where the caller
    sorted them so): a reader looks up only the phrases that can start at a token."""
    index: dict[str, tuple[tuple[str, ...], ...]] = {}
    for phrase in phrases:
        index[phrase[0]] = index.get(phrase[0], ()) + (phrase,)
    return index

DISFLUENCIES = frozenset({"um", "umm", "uh", "uhh", "uhm", "er", "erm", "ehm", "hmm", "hm", "mm", "mmm", "ah", "ahh",
                          "ha", "hah", "haha", "hahaha", "heh", "hehe", "lol"})  # hesitations and laughter

SPLITS: dict[str, tuple[str, ...]] = {
    "uturn": ("u", "turn"), "xray": ("x", "ray"),
    "wanna": ("want", "to"), "gotta": ("got", "to"), "cannot": ("can", "not"), "nevermind": ("never", "mind"),
    "okay": ("ok",), "alright": ("ok",), "estop": ("e", "stop"),
    "anticlockwise": ("anticlockwise",), "counterclockwise": ("anticlockwise",),
    "metres": ("metres",),
    "gimme": ("give", "me"), "lemme": ("let", "me"), "gonna": ("going", "to"), "ya": ("you",),
    # a verb and its particle, or a gesture's two words, as a recogniser runs them together ("stuart backup")
    **{first + second: (first, second) for first, second in (
        ("back", "up"), ("back", "off"), ("step", "back"), ("step", "forward"), ("step", "aside"), ("turn", "left"),
        ("turn", "right"), ("turn", "round"), ("turn", "back"), ("go", "back"), ("move", "back"), ("move", "forward"),
        ("walk", "forward"), ("spin", "around"), ("look", "around"), ("hands", "up"), ("face", "wave"),
        ("shake", "hands"), ("shake", "hand"), ("look", "for"), ("pick", "up"), ("high", "five"))},
}

HARD_STOPS = frozenset({".", ";", "!", "?"})

# words no phrase ends with: a comma after one is a speaker's hesitation ("go to the, um,
# bathroom", "walk towards, er, the door"), not a pause between two clauses
HESITANT = frozenset({"the", "a", "an", "your", "my", "our", "to", "into", "onto", "towards", "toward"})

# exclamations that break into a sentence ("turn left oh never mind", "go to the kitchen oops no
# the bathroom"): a pause is heard before them even where a recogniser wrote none
INTERRUPTING = frozenset({"oh", "ooh", "oops", "whoops", "whoa", "woah"})

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

# a subject and "have", "had", "would" or "will" as one word, as recognisers write them ("you've",
# "you'll"): never inside a name; after a command, the start of a remark ("go to the charging dock
# you've earned a rest", "go to the kitchen you'll find the cup there")
SUBJECT_AND_MODAL = frozenset({"youve", "weve", "ive", "theyve", "youd", "wed", "theyd", "youll", "theyll", "itll",
                               "thatll", "thatd", "itd"})

NP_STOP = SUBJECT_AND_MODAL | BOUNDARY | frozenset({
    "to", "from", "on", "in", "at", "into", "onto", "inside", "near", "next", "by", "with", "for", "off", "of",
    "please", "now", "quickly", "quick", "slowly", "carefully", "immediately", "again", "too", "first", "thanks",
    "thank", "up", "down", "over", "there", "here", "behind", "under", "beside", "between", "below", "above", "around",
    "across", "along", "towards", "toward", "through", "until", "till", "unless", "if", "while", "so",
    "because", "as", "without", "asap", "ok", "gently", "instead", "also", "real", "fast", "safely",
    "straight", "right", "yourself", "which", "who", "where", "whose", "thats", "will", "would", "can",
    "could", "since", "when", "once", "like", "shall", "yeah", "alright", "okay",
    "later", "soon", "today", "tonight", "tomorrow", "afterwards", "sometime",  # when, not what
    "no", "sorry", "oops", "i", "never",  # a correction or a new sentence follows ("go to the kitchen i said")
    "is", "are", "was", "were",  # a clause: "pick up whatever is on the table"
    "you",  # a new clause: "... the kitchen you need a map"
    "cant", "wont", "couldnt", "wouldnt", "shouldnt", "dont", "doesnt", "didnt", "isnt", "arent",  # a tag
    "do", "give",  # a new clause: "when you reach the corner do a high five", "... give everyone a wave"
    "together", "alone",
})

NP_LEADERS = frozenset({"marker", "waypoint", "location", "position", "object", "item"})  # "go to marker kitchen"

RELATIVE = frozenset({"that", "which", "who", "where"})  # end a noun phrase, but not at its start

# what people call the robot (or the room) after a command: "go to the kitchen, mate", "now lad"
ADDRESS_TERMS = frozenset({"buddy", "mate", "pal", "robot", "friend", "sir", "dude", "man", "lad", "lads", "boss",
                           "chief", "champ", "bro", "mister", "madam", "maam", "love", "dear", "darling", "son",
                           "kid", "guys", "folks", "everyone", "everybody", "fella", "fellow", "partner", "sunshine",
                           "captain", "pet", "chap", "guy", "yaar", "bhai", "lass", "hen", "bud", "cobber"})

# thanks and praise after a command: "cheers", "thanks a lot", "much appreciated", "lovely"
THANKS = frozenset({"thanks", "thank", "cheers", "ta", "thx", "ty", "lot", "bunch", "million", "much", "appreciated",
                    "lovely", "great", "brilliant", "cool", "nice", "awesome", "perfect", "wonderful", "fantastic",
                    "legend", "champion", "good"})

TRAILING = ADDRESS_TERMS | THANKS | frozenset({
    "please", "now", "quickly", "slowly", "carefully", "immediately", "again", "too", "first", "you", "ok", "asap",
    "gently", "instead", "also", "fast", "safely", "right", "away", "straight", "real", "quick", "for", "me", "us",
    "as", "well", "if", "can", "could", "will", "would", "possible", "then", "at", "once", "yourself", "soon",
    "there", "here", "over", "shall", "we", "yeah", "alright", "later", "today", "tonight", "tomorrow", "sometime"})

# encouragements said as a clause of their own after a command ("move forward, come on", "off you
# go"): filler, not a new command
SIGN_OFFS: tuple[tuple[str, ...], ...] = (
    # ("chop",) is "chop chop" once the tokenizer has dropped the repeat
    ("come", "on"), ("go", "on"), ("chop",), ("off", "you", "go"), ("there", "you", "go"),
    ("there", "we", "go"), ("here", "we", "go"), ("lets", "go"), ("good", "job"), ("well", "done"), ("nice", "one"),
    ("thank", "you"), ("thanks",), ("cheers",), ("much", "appreciated"), ("if", "you", "dont", "mind"),
    ("thank", "you", "very", "much"), ("thank", "you", "so", "much"), ("thanks", "very", "much"),
    ("thanks", "so", "much"),
    *(("theres", "a", "good", who) for who in ("lad", "boy", "girl", "robot", "chap", "fella", "lass")),
    ("when", "you", "can"), ("when", "youre", "ready"), ("in", "your", "own", "time"), ("no", "rush"),
    ("take", "your", "time"), ("good", "lad"), ("good", "robot"), ("atta", "boy"), ("you", "got", "this"),
    # terms of address of two words ("wave, little guy")
    *((adj, noun) for adj in ("little", "big", "old", "my", "good")
      for noun in ("guy", "buddy", "man", "fella", "friend", "chap", "pal", "mate", "boy", "robot")),
    # hedges that close a sentence without adding to it
    ("you", "know"), ("know", "what", "i", "mean"),
    ("you", "know", "what", "i", "mean"), ("if", "you", "know", "what", "i", "mean"), ("yeah",), ("innit",),
    # a greeting said after a command ("shake my hand, nice to meet you")
    *((how, "to", verb, "you") for how in ("nice", "pleased", "good", "lovely", "great") for verb in ("meet", "see")),
    ("if", "you", "please"),
    # an amount said roughly ("ninety degrees or so", "two metres, give or take")
    ("or", "so"), ("or", "thereabouts"), ("give", "or", "take"), ("more", "or", "less"),
)

WH = frozenset({"what", "whats", "where", "wheres", "who", "whos", "why", "whys", "how", "hows", "when", "whens",
                "which", "whose", "whom", "whatever", "wat"})

AUX = frozenset({"is", "are", "was", "were", "am", "does", "did", "has", "had", "isnt", "arent", "wasnt", "werent",
                 "didnt", "doesnt", "hasnt", "havent", "shall", "might", "must", "should", "shouldnt", "may"})

SUBJECTS = frozenset({"i", "im", "ive", "id", "ill", "we", "were", "weve", "wed", "well", "he", "hes", "she",
                      "shes", "it", "its", "they", "theyre", "theyve", "this", "that", "thats", "there",
                      "theres", "here", "heres", "the", "my", "our", "his", "her", "their", "these", "those",
                      "youre", "youve", "youd", "youll", "everyone", "everybody", "nobody", "someone",
                      "somebody", "people", "mine", "yours", "a", "an", "one", "not", "probably", "if", "thatd",
                      "thatll", "itd", "itll", "theyd", "theyll", "thered", "therell",
                      "because", "although", "though", "unless", "said"})


# Interjections ("great job, now wave", "no, go to the kitchen") neither command nor open a
# statement: the clause after them is read as usual.
MODALS = frozenset({"can", "could", "would", "will", "wont", "wouldnt", "cant", "couldnt"})


# thanks said ahead of a request: "I'd be ever so grateful if you could ...", "it would be great if
# you could ..." (read by clauses._thanks_ahead: as listed phrases they were thousands)
THANKS_AHEAD_OPENERS: tuple[tuple[str, ...], ...] = (
    ("id", "be"), ("i", "would", "be"), ("wed", "be"), ("we", "would", "be"), ("itd", "be"), ("it", "would", "be"),
    ("itll", "be"), ("it", "will", "be"), ("thatd", "be"))
THANKS_AHEAD_OPENERS_BY_FIRST = by_first(sorted(THANKS_AHEAD_OPENERS, key=lambda p: (-len(p), p)))
THANKS_AHEAD_INTENSIFIERS = frozenset({"so", "ever", "really", "very", "most", "super", "truly", "awfully"})
THANKS_AHEAD_FEELINGS = frozenset({"grateful", "glad", "happy", "pleased", "thankful", "delighted", "great", "nice",
                                   "lovely", "helpful", "wonderful", "brilliant", "good", "awesome", "amazing", "kind"})

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

WISH_QUESTIONS_BY_FIRST = by_first(WISH_QUESTIONS)

POLITE: tuple[tuple[str, ...], ...] = tuple(sorted({
    ("please",), ("kindly",), ("just",), ("possibly",), ("perhaps", "you", "could"),
    ("i", "was", "wondering", "if", "you", "could"), ("i", "wonder", "if", "you", "could"),
    ("i", "was", "wondering", "whether", "you", "could"), ("i", "was", "hoping", "you", "could"),
    ("i", "hope", "you", "can"), ("any", "chance", "you", "could"), ("is", "there", "any", "chance", "you", "could"),
    ("would", "you", "kindly"), ("be", "a", "dear", "and"), ("be", "a", "good", "robot", "and"),
    ("feel", "free", "to"), ("you", "may"), ("you", "are", "welcome", "to"), ("youre", "welcome", "to"),
    ("basically",), ("literally",), ("honestly",), ("seriously",), ("essentially",), ("simply",), ("anyway",),
    ("now",), ("ok",), ("so",), ("well",), ("yes",), ("yeah",), ("also",),
    ("hey",), ("quickly",), ("quick",), ("right", "now"), ("maybe",), ("perhaps",), ("actually",), ("oh",),
    ("go", "ahead", "and"), ("lets",), ("let", "us"), ("let", "me", "see", "you"),
    ("i", "want", "you", "to"), ("i", "need", "you", "to"), ("if", "you", "could"), ("if", "you", "would"),
    ("if", "you", "can"), ("if", "you", "will"), ("i", "would", "like", "you", "to"),
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
    ("i", "would", "really", "appreciate", "it", "if", "you", "could"),
    ("id", "really", "appreciate", "it", "if", "you", "could"),
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
    ("please", "to"), ("mind",), ("you", "mind"), ("you", "know", "what"), ("you", "know"), ("first",), ("firstly",),
    ("if", "you", "dont", "mind"), ("if", "you", "do", "not", "mind"), ("if", "you", "please"),
    ("sorry", "to", "bother", "you"), ("sorry", "to", "interrupt"), ("sorry", "to", "disturb", "you"),
    ("come", "on"), ("maybe", "try"), ("again",),
    ("if", "its", "not", "too", "much", "trouble"), ("if", "thats", "ok"), ("if", "thats", "alright"),
} | {  # a need said ahead: "I'm going to need you to ...", "I'll want you to ..."
    (*subject, *when, verb, "you", "to")
    for subject in (("im",), ("i", "am"), ("were",), ("we", "are"), ("ill",), ("i", "will"), ("well",), ("we", "will"))
    for when in ((), ("go", "to"), ("going", "to"), ("gonna",))  # "going" is read as "go"
    for verb in ("need", "want", "ask")
    if not (when and subject[-1] in ("will", "ill", "well"))
} | {  # a request put as a question about what the robot thinks it can do: "do you think you could ..."
    (*opener, verb, *that, "you", modal)
    for opener in (("do", "you"), ("d", "you"), ("dyou",), ())
    for verb in ("think", "reckon", "suppose", "guess")
    for that in ((), ("that",))
    for modal in ("could", "can", "would", "might")
} | {  # a hedge before an order: "I guess just turn right then", "I suppose go to the kitchen"
    (subject, verb, *just) for subject in ("i", "we") for verb in ("guess", "suppose", "reckon")
    for just in ((), ("just",))
} | {("awfully",), ("terribly",), ("ever", "so")},  # "would you mind awfully picking up the cup"
    key=lambda p: (-len(p), p)))

POLITE_BY_FIRST = by_first(POLITE)

# ordinals that number the steps of a plan before a verb ("first find the apple second pick it up")
STEP_ORDINALS = frozenset({"second", "third", "fourth", "fifth"})

CONNECTORS: tuple[tuple[str, ...], ...] = tuple(sorted({
    (",",), ("&",), ("and",), ("then",), ("plus",), ("and", "then"), ("and", "after", "that"), ("and", "afterwards"),
    ("and", "finally"), ("and", "also"), ("and", "next"), ("and", "lastly"), ("after", "that"), ("after", "this"),
    ("after", "which"), ("afterwards",), ("afterward",), ("finally",), ("lastly",), ("first",), ("firstly",),
    ("first", "of", "all"), ("secondly",), ("thirdly",), *((o,) for o in STEP_ORDINALS), ("next",),
    ("then", "after", "that"), ("once", "done"),
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

CONNECTORS_BY_FIRST = by_first(sorted(set(CONNECTORS) | REORDER, key=lambda c: (-len(c), c)))


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

VAGUE_BY_FIRST = by_first(sorted(VAGUE, key=lambda v: (-len(v), v)))

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
    "clap": ("clap", "claps", "applause", "round of applause", "hand clap", "clapping", "applaud", "big clap",
             "put your hands together", "put those hands together"),
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
    "release arm": ("release arm", "arms down", "hands down", "release arms", "arm down", "let go", "let go of me",
                    *(f"let go of {whose} {part}" for whose in ("my", "the", "your", "his", "her")
                      for part in ("arm", "hand", "arms", "hands"))),
}

GESTURE_PHRASES: dict[tuple[str, ...], str] = {tuple(f.split()): name for name, forms in _GESTURE_FORMS.items()
                                               for f in forms}

GESTURES_BY_FIRST = by_first(sorted(GESTURE_PHRASES, key=lambda g: (-len(g), g)))

GESTURE_NOUNS = frozenset({"gesture", "pose", "sign", "move", "motion", "emote", "animation", "action", "thing",
                           "please", "now", "for", "me", "us", "again"})

BODY = frozenset({"hand", "hands", "arm", "arms"})

MOTION_VERBS = frozenset({"go", "move", "walk", "head", "drive", "travel", "proceed", "navigate", "come", "run",
                          "jog", "hurry", "rush", "return", "advance", "roll", "scoot", "shift", "slide", "strafe",
                          "sidestep", "wander", "stroll", "march", "visit", "approach", "reach", "enter", "step",
                          "back", "get", "retreat", "creep", "shuffle", "inch", "hop", "make", "scurry", "dash",
                          "sprint", "zoom", "trot", "amble", "journey", "relocate", "continue", "goto", "gp", "nudge",
                          "edge",
                          "budge", "crawl", "glide", "push", "ease", "wheel", "pop", "nip"})

TURN_VERBS = frozenset({"turn", "rotate", "spin", "pivot", "swivel", "twist", "face", "revolve", "veer", "swing",
                        "yaw"})

PICK_VERBS = frozenset({"pick", "grab", "grasp", "take", "fetch", "collect", "lift", "retrieve", "bring",
                        "carry", "get", "hand", "pass", "give", "snatch", "obtain", "gather", "seize", "acquire",
                        "deliver", "pluck", "procure", "nab", "raise"})

FIND_VERBS = frozenset({"find", "locate", "spot", "seek", "detect", "search", "look", "hunt", "scan", "track",
                        "check"})


# a find verb said as a noun after a light verb: "have a look for", "take a quick look around for"
FIND_NOUNS = frozenset({"look", "search", "hunt", "scan", "check", "peek", "peep", "glance"})

FIND_NOUN_LEADS = frozenset({"have", "take", "do", "give", "make"})

# the verbs that only ever mean stopping the robot (the wider STOP_VERBS below also hold "wait",
# "stay", ...): said again, after a pause in talk, or as a plain command
PLAIN_STOPS = frozenset({"stop", "halt", "freeze"})
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
                "stopped": "stop", "caught": "catch", "shaken": "shake", "done": "do"})
    return out

PAST = _past(ALL_VERBS)

STOP_PHRASES: tuple[tuple[str, ...], ...] = (
    ("thats", "enough"), ("that", "is", "enough"), ("enough",), ("emergency", "stop"), ("e", "stop"), ("whoa",),
    ("woah",), ("never", "mind"), ("forget", "it"), ("no", "stop"), ("not", "now"), ("dont", "move"),
    ("do", "not", "move"), ("dont", "go", "anywhere"), ("do", "not", "go", "anywhere"), ("no", "no"),
    ("no", "more"), ("stop",), ("halt",), ("freeze",), ("red", "light"), ("hands", "off"), ("easy",),
    ("steady",), ("dont", "walk"), ("dont", "do", "anything"), ("dont", "do", "that"), ("stop", "it"),
)

STOP_PHRASES_BY_FIRST = by_first(sorted(STOP_PHRASES, key=lambda p: (-len(p), p)))

TURN_IDIOMS: tuple[tuple[str, ...], ...] = (("about", "face"), ("about", "turn"), ("u", "turn"), ("one", "eighty"),
                                            ("180",), ("turnaround",), ("other", "way"), ("the", "other", "way"))

TURN_IDIOMS_BY_FIRST = by_first(sorted(TURN_IDIOMS, key=lambda p: (-len(p), p)))

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

REQUESTS_BY_FIRST = by_first(sorted(REQUESTS + WANTS, key=lambda p: (-len(p), p)))


# the speaker as the subject of a gesture the robot shares: "let me shake your hand", "can I hug
# you", "may we give you a high five" ask the robot for that gesture; other "can I ..." are
# questions about the speaker ("can I go to the kitchen?")
SPEAKER_OPENERS: tuple[tuple[str, ...], ...] = (
    ("let", "me"), ("can", "i"), ("could", "i"), ("may", "i"), ("can", "we"), ("could", "we"), ("may", "we"))

SPEAKER_OPENERS_BY_FIRST = by_first(SPEAKER_OPENERS)


# what a speaker says before correcting the clause just said: "go to the kitchen, no, the
# bathroom", "pick up the cup, sorry, I mean the bottle", "turn left, no wait, right"
CORRECTIONS: tuple[tuple[str, ...], ...] = (
    ("no",), ("no", "wait"), ("wait", "no"), ("sorry",), ("i", "mean"), ("i", "meant"), ("oops",),
    ("or", "rather"), ("rather",), ("make", "that"), ("make", "it"), ("scratch", "that"), ("correction",),
    ("my", "mistake"), ("my", "bad"), ("not", "that"), ("i", "said"),
)

CORRECTIONS_BY_FIRST = by_first(sorted(CORRECTIONS, key=lambda c: (-len(c), c)))

# stop verbs that stop only with one of these words next ("hold on", "cut it out", "never mind";
# "" is the end of the text); the rest stop whatever follows
# how long a stop is meant to last, said after it ("stop for a second", "freeze a moment"): the
# robot stops either way, so these words only say more about the stop
PAUSE_SPANS: tuple[tuple[str, ...], ...] = tuple(sorted({
    (a, unit) for a in ("a", "one", "1") for unit in ("second", "sec", "moment", "minute", "min", "mo", "tick", "jiffy")
} | {("a", "bit"), ("a", "while"), ("a", "little"), ("a", "little", "bit"), ("a", "few", "seconds"),
     ("two", "seconds"), ("a", "couple", "of", "seconds"), ("just", "a", "second"), ("just", "a", "moment"),
     ("now",), ("there",), ("right", "there"), ("where", "you", "are"), ("right", "where", "you", "are")},
    key=lambda p: (-len(p), p)))
PAUSE_SPANS_BY_FIRST = by_first(PAUSE_SPANS)

STOP_VERB_NEEDS: dict[str, frozenset[str]] = {
    "stand": frozenset({"still", "there", "by", "put", "here", "fast", "your", "right", "at", "in", "near", "beside",
                        "inside"}),
    "never": frozenset({"mind"}),
    "forget": frozenset({"it", "that", "about", "everything", "this"}),
    "cut": frozenset({"it", "that", "out"}),
    **dict.fromkeys(("hang", "hold"), frozenset({"on", "it", "up", "still", "your", "position", "tight", "off",
                                                 "everything", "there"})),
    **dict.fromkeys(("end", "terminate", "kill", "interrupt"), frozenset({"it", "that", "the", "this", "everything",
                                                                           "mission", "task", "now", "all"})),
    "break": frozenset({"off"}),
    "chill": frozenset({"out", ""}),
    "e": frozenset({"stop"}),
    "emergency": frozenset({"stop", "halt", "brake", ""}),
    "quit": frozenset({"it", "that", "moving", "move", "now", "", "please"}),
}

# gesture verbs that name their gesture whatever follows ("wave at them", "give a clap")
GESTURE_VERB_NAMES: dict[str, str] = {"wave": "wave", "greet": "wave", "clap": "clap", "applaud": "clap", "hug": "hug",
                                      "cuddle": "hug", "embrace": "hug", "reject": "reject"}

# words after "get" that make it no "get the object": "get going", "get ready", "get to the
# kitchen" (a walk), "get over it"; "get a cup", "get it", "get some water" still are
GET_IDIOM_NEXT = frozenset({"going", "go", "moving", "move", "up", "down", "out", "ready", "closer", "away", "lost",
                            "along", "on", "off", "in", "inside", "started", "here", "over", "there", "a", "an", "rid",
                            "it", "real", "better", "well", "some", "dressed", "to", "back", "home"})

# Taking back what was just said: everything asked before it in the utterance is dropped
# ("go to the kitchen, just kidding"; "walk to the kitchen and ..., I'm joking").
RETRACTIONS: tuple[tuple[str, ...], ...] = (
    ("just", "kidding"), ("only", "kidding"), ("kidding",), ("im", "kidding"), ("just", "joking"), ("only", "joking"),
    ("joking",), ("im", "joking"), ("jk",), ("just", "messing"), ("only", "messing"), ("messing", "with", "you"),
    ("just", "teasing"), ("only", "teasing"), ("pulling", "your", "leg"), ("not", "really"),
    # "i am joking", "I'm only kidding", "I was just teasing" ("im messing" is below, "im teasing" is none)
    *((*subject, *adverb, word) for subject in (("im",), ("i", "am"), ("i", "was"))
      for adverb in ((), ("only",), ("just",)) for word in ("joking", "kidding", "messing", "teasing")
      if subject != ("im",) or adverb),
    ("forget", "it"), ("forget", "that"), ("forget", "everything"), ("forget", "all", "that"), ("cancel", "that"),
    ("on", "second", "thought"), ("on", "second", "thoughts"), ("dont", "bother"), ("nah",), ("no", "dont"),
    ("i", "take", "that", "back"), ("belay", "that"), ("as", "you", "were"), ("dont",), ("do", "not"),
    ("dont", "worry"), ("no", "worries"), ("ignore", "that"), ("ignore", "me"),
    ("disregard", "that"), ("scrap", "that"), ("forget", "about", "it"), ("dont", "worry", "about", "it"),
    ("having", "a", "laugh"), ("only", "having", "a", "laugh"), ("just", "having", "a", "laugh"),
    ("only", "messing"), ("just", "messing"), ("im", "messing"), ("only", "teasing"), ("just", "teasing"),
    ("pulling", "your", "leg"), ("just", "pulling", "your", "leg"), ("only", "pulling", "your", "leg"),
    # after a request in the same breath it takes that request back; alone it is a stop (stopping.py)
    ("never", "mind"), ("nevermind",),
)

RETRACTIONS_BY_FIRST = by_first(sorted(RETRACTIONS, key=lambda r: (-len(r), r)))
SIGN_OFFS_BY_FIRST = by_first(sorted(SIGN_OFFS, key=lambda r: (-len(r), r)))

# A question tag turns the sentence before it into a question ("..., right?", "..., wouldn't it?"):
# one of these words alone, or an auxiliary and a pronoun. "..., will you?" after a command is a
# request, not a question (see forms.question_tag).
TAG_WORDS = frozenset({"right", "correct", "yeah", "innit", "eh", "true", "yes", "no", "huh", "surely"})
TAG_PRONOUNS = frozenset({"it", "that", "they", "he", "she", "we", "i", "there", "you", "this"})
TAG_AUX = frozenset({"is", "isnt", "are", "arent", "was", "wasnt", "were", "werent", "do", "dont", "does",
                     "doesnt", "did", "didnt", "have", "havent", "has", "hasnt", "had", "hadnt", "will", "wont",
                     "would", "wouldnt", "can", "cant", "could", "couldnt", "should", "shouldnt", "shall", "am",
                     "aint", "might", "must"})
REQUEST_TAGS = frozenset({"will", "wont", "would", "can", "could"})  # "..., will you?" after a command asks
NEGATIVE_TAG_AUX = frozenset(a for a in TAG_AUX if a.endswith("nt"))  # "... can't you": a tag even unwritten

# words that label an item of a spoken list ("item one, go to station 2; item two, ..."), not a place
LIST_LABELS = frozenset({"item", "step", "point", "task", "number", "part", "stage"})

# a sentence opening with these is about the past, not a command ("back when you first arrived, ...")
TIME_OPENERS = frozenset({("back", "when"), ("back", "then"), ("back", "in"), ("way", "back"),
                          ("remember", "when"), ("remember", "how"), ("remember", "the")})  # a memory

# parts of the body: a phrase naming one says how to do a thing ("with your teeth", "on one leg"),
# which the robot cannot choose, not which thing or place is meant
BODY_PARTS = frozenset({"hand", "hands", "arm", "arms", "leg", "legs", "foot", "feet", "teeth", "tooth", "head",
                        "eyes", "mouth", "nose", "knee", "knees", "finger", "fingers", "toes", "elbow", "tongue"})

# a subject and "is" as one word, as recognisers write them without the apostrophe ("it's" -> "its")
SUBJECT_AND_IS = frozenset({"its", "thats", "theres", "hes", "shes", "whats"})
# a subject and "are" or "am" as one word: before an ing-form, the start of a statement ("we're heading home")
SUBJECT_AND_BE = SUBJECT_AND_IS | frozenset({"were", "youre", "theyre", "im"})

# words of time: the robot acts now, so "in twenty minutes" or "later" is never filler
TIMES = frozenset({"second", "seconds", "minute", "minutes", "hour", "hours", "min", "mins", "sec", "secs", "later",
                   "tomorrow", "tonight", "today", "morning", "afternoon", "evening", "week", "day", "past", "oclock",
                   "noon", "midnight", "pm"})

# a step asked for once more, said as a clause of its own ("turn left, and again", "... and then
# do it again", "do the same to the left"); "turn left again" is one turn ("again" only trails it)
REPEATS: tuple[tuple[str, ...], ...] = (
    ("again",), ("one", "more", "time"), ("once", "more"), ("same", "again"), ("repeat", "that"), ("repeat", "it"),
    *((verb, what, "again") for verb in ("do", "try") for what in ("it", "that", "this")),
    ("do", "the", "same"), ("the", "same"), ("same", "thing"), ("do", "the", "same", "thing"),
)
REPEATS_BY_FIRST = by_first(sorted(REPEATS, key=lambda r: (-len(r), r)))

# words before a thing or place said instead of the last one, with no pause ("pick up the apple
# hmm actually the book"): a noun phrase ends before them
INSTEAD = frozenset({"actually", "oh", "ah", "hmm"})
