"""Voice missions: utterances -> plans -> compiled trees, run one after another (docs/missions.md)."""
