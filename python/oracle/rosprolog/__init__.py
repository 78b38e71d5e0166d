"""KnowRob's client protocol, rosprolog, in front of this project's Prolog (docs/knowrob.md).

``protocol`` keeps the queries clients open (ids, modes, statuses) and asks Prolog for pages of
rosprolog-encoded solutions; ``backend`` says where that Prolog runs; two doors carry the
protocol: ``ros`` (ROS 1 services through a small rospy node, ``node.py``, run by Debian's
python3) and ``rosbridge`` (a websocket route of the live service). No module here imports
rospy: ROS 1 lives in Debian's Python, not in this package's.
"""
