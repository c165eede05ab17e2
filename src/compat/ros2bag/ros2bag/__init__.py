"""`ros2 bag`: record topics to a rosbag2 folder of MCAP files, show what a bag holds, play it back."""
