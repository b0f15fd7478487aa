"""stuart_bt: behaviour trees and HTN missions for the Unitree G1 humanoid "Stuart".

Data flow: utterance -> wake filter -> intents -> HTN planner -> compiler -> executor -> skill
leaves -> daemon client -> daemon subprocess -> backend (dry, sim, unitree). See docs/.
"""

__version__ = "0.1.0"
