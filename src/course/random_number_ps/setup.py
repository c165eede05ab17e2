from setuptools import find_packages, setup

package_name = 'random_number_ps'

setup(
    name=package_name,
    version='0.1.0',
    packages=find_packages(exclude=['test']),
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml']),
    ],
    install_requires=['setuptools'],
    zip_safe=True,
    maintainer='Owl Kit Lab',
    maintainer_email='team@owlkitlab.invalid',
    description='Random number publisher/subscriber and the section 3.5 exercises.',
    license='Apache-2.0',
    tests_require=['pytest'],
    entry_points={
        'console_scripts': [
            'random_number_publisher = random_number_ps.random_number_publisher:main',
            'random_number_subscriber = random_number_ps.random_number_subscriber:main',
            'counter_publisher = random_number_ps.counter_publisher:main',
            'turtle_random_velocity = random_number_ps.turtle_random_velocity:main',
        ],
    },
)
