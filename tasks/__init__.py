"""HTN task domain (filled by the voice-missions work)."""
