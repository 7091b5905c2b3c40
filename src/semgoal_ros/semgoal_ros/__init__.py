"""What every semgoal node shares on the ROS side: topic names, QoS, message <-> core conversions, run_node."""
