"""ROS 2 Humble beside our Jazzy: both graph message layouts, a Humble module twin, the discovery bridge."""
