"""The seams every stage shares, and nothing else: the clock behind every timeout, the event
stream every view reads, the blackboard and the world state on it, expressions, the catalogue
of node kinds and gestures, strict JSON files, did-you-mean. Imports nothing of the rest of the
package."""
